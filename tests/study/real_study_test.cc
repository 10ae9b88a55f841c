// The real record (studies/real-steel.toml): with EI, cDI and gamma identified from the free decay (rho nominal),
// every cost's model must put the first five bending modes within 1.5 % of the record's measured peaks. A
// one-parameter stiffness scale cannot do that unless the model's frequency ratios match the beam's (a clamped
// Timoshenko beam with a light tip mass): it tests the model, the import, the free-decay fit and the pairing by
// frequency together. 1.5 % is about 12 bins at mode 5 and 1 bin at mode 1 (df = 0.125 Hz); the spread of the
// measured frequencies about a single scale is under 1 %.
#include "study/real/real_study.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/errors.h"

namespace beamid::study {
namespace {

TEST(RealSteel, IdentifiedFrequenciesMatchTheMeasuredPeaks) {
  const std::string file = std::string(BEAMID_SOURCE_DIR) + "/studies/real-steel.toml";
  const RealStudySpec spec = load_real_study(file);
  const std::string out = std::string(BEAMID_BINARY_DIR) + "/real-steel-test";
  std::ostringstream log;
  ASSERT_EQ(run_real_study(spec, out, log), 0) << log.str();
  std::ifstream in(out + "/modes.csv");
  std::string line;
  std::getline(in, line);
  ASSERT_EQ(line,
            "candidate,cost,record,mode,measured_frequency_hz,measured_uncertainty_hz,identified_frequency_hz,"
            "identified_damping_ratio,discretisation_error_hz");
  std::map<std::string, int> rows;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string candidate, cost, record, mode, measured, uncertainty, identified, zeta;
    std::getline(row, candidate, ',');
    std::getline(row, cost, ',');
    std::getline(row, record, ',');
    std::getline(row, mode, ',');
    std::getline(row, measured, ',');
    std::getline(row, uncertainty, ',');
    // The measured frequency's uncertainty (signal/measured_modes.h): positive, and below 2 % of it on this record,
    // whose modes drift by 0.1-0.9 % between segments (a larger u would say the estimator took a neighbour).
    const double u = std::stod(uncertainty);
    EXPECT_GT(u, 0) << cost << " mode " << mode;
    EXPECT_LT(u, 0.02 * std::stod(measured)) << cost << " mode " << mode;
    std::getline(row, identified, ',');
    std::getline(row, zeta, ',');
    const double m = std::stod(measured), f = std::stod(identified), z = std::stod(zeta);
    EXPECT_NEAR(f / m, 1, 0.015) << cost << " mode " << mode;
    EXPECT_GT(z, 0) << cost << " mode " << mode;
    EXPECT_LT(z, 0.05) << cost << " mode " << mode;  // a steel beam: lightly damped
    ++rows[cost];
  }
  for (const auto& cost : spec.costs) EXPECT_EQ(rows[cost], 5) << cost;
  // The measured peaks are the record's, near the values SOURCE.md lists (6.62, 41.38, 116.9, 229.8, 380.5 Hz).
}

// A study file in a scratch folder beside copies of two synthetic strip records (studies/data/synthetic-strip).
std::string scratch_study(const std::string& name, const std::string& body) {
  const std::filesystem::path dir = std::filesystem::path(BEAMID_BINARY_DIR) / ("real-study-" + name);
  std::filesystem::create_directories(dir);
  const std::filesystem::path data = std::filesystem::path(BEAMID_SOURCE_DIR) / "studies/data/synthetic-strip";
  for (const char* file : {"strip_L200.csv", "strip_L200.toml", "strip_L300.csv", "strip_L300.toml"})
    std::filesystem::copy_file(data / file, dir / file, std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir / "study.toml") << body;
  return (dir / "study.toml").string();
}

const char* kTwoRecords = R"(
[study]
name = "two-lengths"
question = "test"

[[record]]
name = "short"
file = "strip_L200.csv"
beam = "strip_L200.toml"
peaks_hz = [56.31, 381.3, 990.0]

[[record]]
name = "long"
file = "strip_L300.csv"
beam = "strip_L300.toml"
peaks_hz = [25.07, 172.7, 473.3]

[beam]
file = "strip_L300.toml"
)";

std::string load_error(const std::string& name, const std::string& body) {
  try {
    load_real_study(scratch_study(name, body));
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(RealStudy, TwoLengthsFittedJointlyRecoverTheSharedModulusAndTheBoard) {
  // Two of the synthetic strip's records (make_records.sh: truth E = 71 GPa, so EI = 71e9 x 0.025 x 0.003^3 / 12 =
  // 3.99375 N m^2, a 6.0 g board 58 mm inboard of the tip; 1 % noise; truth N = 48, fitted at N = 16) from the
  // nominal beams (EI 3.88, 5 g, 60 mm). The modal cost fits three modes per record; the frequencies' noise-induced
  // error is ~1e-5 relative and the N = 16 discretisation error ~1e-5 (REPORT 1), so EI within 0.2 %, the mass within
  // 2 % and the positions within 1 mm (measured: 3e-6, 5e-4 and 0.03 mm off) say the joint fit found the truth, not the
  // start (2.9 %, 20 %, 2 mm away).
  const RealStudySpec spec = load_real_study(scratch_study("joint", std::string(kTwoRecords) + R"(
[fit]
elements = 16
estimate = ["EI", "attachment1.m"]
per_record = ["attachment1.x", "cDI"]
costs = ["modal"]
bounds = { "attachment1.m" = [0.001, 0.02], cDI = [1e-6, 1e-3] }
)"));
  ASSERT_EQ(spec.records.size(), 2u);
  ASSERT_EQ(spec.candidates.size(), 1u);
  std::ostringstream log;
  const RealResults results = compute_real_study(spec, log);
  ASSERT_EQ(results.fits.size(), 1u);
  const RealFit& f = results.fits.front();
  ASSERT_EQ(f.status, "converged") << log.str();
  std::map<std::string, double> estimate;
  for (const auto& p : f.parameters) estimate[p.key] = p.estimate;
  EXPECT_NEAR(estimate["EI"] / 3.99375, 1, 2e-3);
  EXPECT_NEAR(estimate["attachment1.m"] / 0.006, 1, 2e-2);
  EXPECT_NEAR(estimate["record1.attachment1.x"], 0.142, 1e-3);
  EXPECT_NEAR(estimate["record2.attachment1.x"], 0.242, 1e-3);
  ASSERT_EQ(f.identified_hz.size(), 2u);
  EXPECT_LT(f.rms_misfit, 5e-3);
  // The tables list both records' modes.
  const RenderedFiles files = render_real_study(spec, results);
  const auto modes = std::find_if(files.begin(), files.end(), [](const Rendered& r) { return r.path == "modes.csv"; });
  ASSERT_NE(modes, files.end());
  EXPECT_NE(modes->text.find("\"short\""), std::string::npos);
  EXPECT_NE(modes->text.find("\"long\""), std::string::npos);
  // Each record's verdict (issue 31): some candidate fits it within 2 u at every mode (u the measured frequency's
  // uncertainty; a synthetic record's modes are steady, so u is the noise's, and the fit at the truth lands within
  // it). A record measured 10 % off at one mode (as the UnB beam's tip masses are by one EI) is fitted by none, and
  // the report says so.
  const auto report = [&](const RealResults& r) {
    const RenderedFiles rendered = render_real_study(spec, r);
    return std::find_if(rendered.begin(), rendered.end(), [](const Rendered& x) { return x.path == "report.md"; })
        ->text;
  };
  EXPECT_NE(report(results).find("`[true]` some candidate model fits record 'long' within 2 u at every mode"),
            std::string::npos)
      << report(results);
  RealResults off = results;
  off.records[1].measured_hz[0] *= 1.1;
  const std::string text = report(off);
  EXPECT_NE(text.find("`[false]` some candidate model fits record 'long' within 2 u at every mode"), std::string::npos)
      << text;
  EXPECT_NE(text.find(": no candidate model fits it"), std::string::npos) << text;
  // A fit whose two measured modes of one record pair with one model mode (A4) fits neither that record nor its
  // claim, whatever its misfits (the ninth pass: said nowhere).
  RealResults shared = results;
  shared.fits[0].shared_mode = "the measured 25.07 and 172.7 Hz of record 2 pair with one model mode, 25.07 Hz (A4)";
  shared.fits[0].shared_record = 1;
  const std::string a4 = report(shared);
  EXPECT_NE(a4.find(", but the measured 25.07 and 172.7 Hz of record 2 pair with one model mode"), std::string::npos)
      << a4;
  EXPECT_NE(a4.find("`[false]` some candidate model fits record 'long'"), std::string::npos) << a4;
  EXPECT_NE(a4.find("`[true]` some candidate model fits record 'short'"), std::string::npos) << a4;
  EXPECT_NE(text.find("`[true]` some candidate model fits record 'short'"), std::string::npos) << text;
}

// What is found only when a record is read names the key's line too (the eighth pass's RQ08, RQ19: the study file
// alone): a start after the record's end, a peak above its Nyquist frequency.
std::string run_error(const std::string& name, const std::string& body) {
  std::ostringstream log;
  try {
    compute_real_study(load_real_study(scratch_study(name, body)), log);
  } catch (const InputError& e) {
    return e.what();
  }
  return "ran";
}

TEST(RealStudy, ErrorsFoundWhenARecordIsReadNameTheKeysLine) {
  const std::string fit = "\n[fit]\nestimate = [\"EI\"]\ncosts = [\"modal\"]\nmax_evaluations = 10\n";
  std::string late = kTwoRecords;
  late.replace(late.find("peaks_hz = [25.07"), 0, "start_s = 500.0\n");  // line 16 of the study file
  const std::string start = run_error("late", late + fit);
  EXPECT_EQ(start.find(scratch_study("late", late + fit) + ":16: "), 0u) << start;
  EXPECT_NE(start.find("strip_L300.csv: record 'long'.start_s = '500' s: must lie inside the record"),
            std::string::npos)
      << start;
  std::string same = kTwoRecords;  // the second record is the first's file and window under another name
  same.replace(same.find("strip_L300.csv"), 14, "strip_L200.csv");
  same.replace(same.find("[25.07, 172.7, 473.3]"), 21, "[56.31, 381.3, 990.0]");
  const std::string twice = run_error("same", same + fit);
  EXPECT_NE(twice.find("record 'long' holds samples of record 'short'"), std::string::npos) << twice;
  same.replace(same.find("peaks_hz = [56.31, 381.3, 990.0]", same.find("name = \"long\"")), 0, "start_s = 0.01\n");
  const std::string shifted = run_error("shifted", same + fit);  // the same file and channel from 0.01 s on
  EXPECT_NE(shifted.find("record 'long' holds samples of record 'short'"), std::string::npos) << shifted;
  std::string high = kTwoRecords;
  high.replace(high.find("990.0]"), 5, "9e5");  // line 10; the record is sampled at 4 kHz
  const std::string peak = run_error("high", high + fit);
  EXPECT_NE(peak.find("study.toml:10: record 'short'.peaks_hz = 9e+05 Hz: must lie below the record's Nyquist"),
            std::string::npos)
      << peak;
}

TEST(RealStudy, ARecordLeftOutOfAPerRecordParameterKeepsItsNominalValue) {
  // fixed = { short = ["cDI"] }: record 1's damping is not estimated (its beam file's value stays), record 2's is.
  const RealStudySpec spec = load_real_study(scratch_study("fixed", std::string(kTwoRecords) + R"(
[fit]
estimate = ["EI"]
per_record = ["cDI"]
costs = ["modal"]
max_evaluations = 10
fixed = { short = ["cDI"] }
)"));
  std::ostringstream log;
  const RealResults results = compute_real_study(spec, log);
  ASSERT_EQ(results.fits.size(), 1u);
  std::vector<std::string> keys;
  for (const auto& p : results.fits.front().parameters) keys.push_back(p.key);
  EXPECT_EQ(keys, (std::vector<std::string>{"EI", "record2.cDI"})) << log.str();
}

TEST(RealStudy, BadRecordsAndCandidatesAreErrorsNamingTheLineAndKey) {
  const std::string fit = "\n[fit]\nestimate = [\"EI\"]\ncosts = [\"modal\"]\n";
  EXPECT_EQ(load_error("good", std::string(kTwoRecords) + fit), "accepted");
  // A bound of a key no model estimates.
  EXPECT_NE(load_error("bound", std::string(kTwoRecords) + fit + "bounds = { gamma = [0.01, 1.0] }\n")
                .find("fit.bounds.gamma: 'gamma' is estimated by no model"),
            std::string::npos);
  // A candidate that sets a value the beams lack, and one that fits a record the study does not have.
  const std::string set_missing = std::string(kTwoRecords) + fit +
                                  "\n[[candidate]]\nname = \"two boards\"\nvalues = { \"attachment2.m\" = 0.01 }\n";
  EXPECT_NE(load_error("values", set_missing).find("candidate 'two boards', record 'short'"), std::string::npos)
      << load_error("values", set_missing);
  // A candidate's values meet the bounds the beam file's own met: a 1e9 kg tip and a 1e-12 N m/rad clamp spring were
  // accepted and their fits failed with no reason (the second adversarial pass's N506-N509).
  for (const auto& [name, values, key] : {std::tuple{"heavy", "m = 1e9", "m = 1e+09"},
                                          std::tuple{"soft", "\"support.k_theta\" = 1e-12", "support.k_theta"},
                                          std::tuple{"flywheel", "J_o = 1e6", "J_o = 1e+06"}}) {
    const std::string text =
        std::string(kTwoRecords) + fit + "\n[[candidate]]\nname = \"" + name + "\"\nvalues = { " + values + " }\n";
    const std::string error = load_error(name, text);
    EXPECT_NE(error.find(std::string("candidate '") + name + "'"), std::string::npos) << error;
    EXPECT_NE(error.find(std::string("values: ") + key), std::string::npos) << error;
  }
  // A key both shared and per record in [fit] itself, listed after another (the sixth pass's S460: run, exit 3).
  const std::string shared_and_own =
      std::string(kTwoRecords) + "\n[fit]\nestimate = [\"EI\"]\nper_record = [\"cDI\", \"EI\"]\ncosts = [\"modal\"]\n";
  EXPECT_NE(load_error("own", shared_and_own).find("fit.per_record"), std::string::npos)
      << load_error("own", shared_and_own);
  EXPECT_NE(load_error("own", shared_and_own).find("is also in estimate"), std::string::npos)
      << load_error("own", shared_and_own);
  // A study name that is a path, or empty, would write its tables outside results/ or into it (the twelfth pass's P2).
  for (const char* name : {"../victim", ""}) {
    std::string text = std::string(kTwoRecords) + fit;
    text.replace(text.find("\"two-lengths\""), std::string("\"two-lengths\"").size(), std::string("\"") + name + "\"");
    EXPECT_NE(load_error("named", text).find("study.name = '" + std::string(name) + "': must be a non-empty word"),
              std::string::npos)
        << load_error("named", text);
  }
  // An empty candidate name, and a start value outside the candidate's bounds (the fourth pass's Q429, Q440).
  const std::string unnamed = std::string(kTwoRecords) + fit + "\n[[candidate]]\nname = \"\"\n";
  EXPECT_NE(load_error("unnamed", unnamed).find("must be a non-empty name"), std::string::npos)
      << load_error("unnamed", unnamed);
  // A quote or a newline in a name broke the CSV tables' rows (the second adversarial pass of 2026-11-28, P1).
  for (const char* name : {"a\\\"b", "a\\nb"}) {
    const std::string quoted = std::string(kTwoRecords) + fit + "\n[[candidate]]\nname = \"" + name + "\"\n";
    EXPECT_NE(load_error("quoted", quoted).find("must hold no quote or control character"), std::string::npos)
        << load_error("quoted", quoted);
  }
  const std::string outside =
      std::string(kTwoRecords) + fit +
      "\n[[candidate]]\nname = \"stiff\"\nvalues = { EI = 1000.0 }\nbounds = { EI = [1.0, 10.0] }\n";
  EXPECT_NE(load_error("outside", outside).find("must lie in its bounds [1, 10]"), std::string::npos)
      << load_error("outside", outside);
  // A start (the beam's value) outside a candidate's bounds was found at fit time, every fit a failed row (the second
  // adversarial pass of 2026-11-28, P6).
  const std::string narrow =
      std::string(kTwoRecords) + fit + "\n[[candidate]]\nname = \"narrow\"\nbounds = { EI = [1e6, 2e6] }\n";
  EXPECT_NE(load_error("narrow", narrow).find("lies outside its bounds [1e+06, 2e+06]"), std::string::npos)
      << load_error("narrow", narrow);
  const std::string unknown_record =
      std::string(kTwoRecords) + fit + "\n[[candidate]]\nname = \"alone\"\nrecords = [\"medium\"]\n";
  EXPECT_NE(load_error("records", unknown_record).find("candidate1.records"), std::string::npos)
      << load_error("records", unknown_record);
  // Two candidates of one name; an unknown key in a candidate.
  const std::string twice =
      std::string(kTwoRecords) + fit + "\n[[candidate]]\nname = \"a\"\n\n[[candidate]]\nname = \"a\"\n";
  EXPECT_NE(load_error("twice", twice).find("candidate2.name"), std::string::npos) << load_error("twice", twice);
  const std::string typo = std::string(kTwoRecords) + fit + "\n[[candidate]]\nname = \"a\"\nestimates = [\"EI\"]\n";
  EXPECT_NE(load_error("typo", typo).find("estimates"), std::string::npos) << load_error("typo", typo);
  // A record's rate must be positive (the key named with its record).
  std::string rate = kTwoRecords;
  rate.replace(rate.find("peaks_hz = [25.07"), 0, "sample_rate_hz = 0.0\n");
  EXPECT_NE(load_error("rate", rate + fit).find("record2.sample_rate_hz"), std::string::npos)
      << load_error("rate", rate + fit);
  // The route's keys: start_from is the first cost, with another after it; a seed without starts seeds nothing.
  const std::string two_costs = "\n[fit]\nestimate = [\"EI\"]\ncosts = [\"modal\", \"spike-smooth\"]\n";
  EXPECT_EQ(load_error("route", std::string(kTwoRecords) + two_costs + "starts = 4\nstart_from = \"modal\"\n"),
            "accepted");
  EXPECT_NE(load_error("route", std::string(kTwoRecords) + two_costs + "start_from = \"spike-smooth\"\n")
                .find("fit.start_from = 'spike-smooth': must be the first of fit.costs ('modal')"),
            std::string::npos);
  EXPECT_NE(load_error("route", std::string(kTwoRecords) + fit + "start_from = \"modal\"\n").find("fit.start_from"),
            std::string::npos);
  EXPECT_NE(load_error("route", std::string(kTwoRecords) + fit + "seed = 3\n").find("seeds fit.starts > 1"),
            std::string::npos);
  // A record left out of one per-record parameter (fixed): keyed by a record's name, listing per_record keys.
  const std::string per_record = "\n[fit]\nestimate = [\"EI\"]\nper_record = [\"cDI\"]\ncosts = [\"modal\"]\n";
  EXPECT_NE(load_error("fixed", std::string(kTwoRecords) + per_record + "fixed = { medium = [\"cDI\"] }\n")
                .find("fit.fixed.medium"),
            std::string::npos);
  EXPECT_NE(load_error("fixed", std::string(kTwoRecords) + per_record + "fixed = { short = [\"EI\"] }\n")
                .find("must be one of cDI"),
            std::string::npos)
      << load_error("fixed", std::string(kTwoRecords) + per_record + "fixed = { short = [\"EI\"] }\n");
  // One window.
  EXPECT_NE(load_error("windows", std::string(kTwoRecords) + fit + "windows = 1\n").find("fit.windows"),
            std::string::npos);
  // The fifth pass's: two records of one name (R437), and a key both shared and per record (R428, which failed every
  // fit at run time with exit 3).
  std::string same_names = kTwoRecords;
  same_names.replace(same_names.find("name = \"long\""), 13, "name = \"short\"");
  EXPECT_NE(load_error("names", same_names + fit).find("must differ from every other record's"), std::string::npos)
      << load_error("names", same_names + fit);
  const std::string both =
      std::string(kTwoRecords) + fit + "\n[[candidate]]\nname = \"a\"\nestimate = [\"EI\"]\nper_record = [\"EI\"]\n";
  EXPECT_NE(load_error("both", both).find("is also in estimate"), std::string::npos) << load_error("both", both);
}

}  // namespace
}  // namespace beamid::study
