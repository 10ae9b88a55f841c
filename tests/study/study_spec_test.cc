// Study files are strict: every error names file:line, the key, the value and the violated constraint.
#include "study/spec/study_spec.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "core/errors.h"
#include "study/plan/plan.h"

namespace beamid::study {
namespace {

const char* kValid = R"([study]
name = "mini"
question = "q"
seed = 5

[truth]
beam = "banks-aluminium"
samples = 256
force_x_m = 0.32
pulse_width_s = 0.004

[fit]
estimate = ["EI", "rho"]

[starts.near]
EI = 1.05
rho = 0.95

[methods.direct]
strategy = "direct"

[sweep]
elements = [4, 8]
cost = ["time", "spike-smooth"]
noise = [0.0, 0.01]
replicates = 3
method = ["direct"]
start = ["near"]
)";

std::string error_of(const std::string& text) {
  try {
    parse_study(text, "s.toml", ".");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto p = text.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  return text.replace(p, from.size(), to);
}

TEST(StudySpec, ReadsAValidFile) {
  const StudySpec s = parse_study(kValid, "s.toml", ".");
  EXPECT_EQ(s.name, "mini");
  EXPECT_EQ(s.seed, 5u);
  EXPECT_EQ(s.truth.elements, 48);  // default N_truth
  EXPECT_EQ(s.truth.experiment.samples, 256);
  EXPECT_EQ(s.sweep.elements, (std::vector<int>{4, 8}));
  EXPECT_EQ(s.start("near").factor.at("rho"), 0.95);
  EXPECT_EQ(s.fit.damping_tolerance, s.fit.success_tolerance);
  EXPECT_EQ(s.outputs.overlay_elements, 8);  // largest N by default
}

TEST(StudySpec, EveryCommittedStudyFileLoads) {
  // The studies `make study` runs and CI's smoke study: a new refusal must not refuse what the project itself runs.
  int loaded = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(BEAMID_SOURCE_DIR) / "studies")) {
    if (e.path().extension() != ".toml") continue;
    const std::string first_table = [&] {
      std::ifstream in(e.path());
      std::string line;
      while (std::getline(in, line))
        if (!line.empty() && line.front() == '[') return line;
      return std::string();
    }();
    if (first_table != "[study]") continue;
    std::ifstream in(e.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find("\n[truth]") == std::string::npos) continue;  // a real-record study (study/real)
    EXPECT_NO_THROW(load_study(e.path().string())) << e.path();
    ++loaded;
  }
  EXPECT_GE(loaded, 15);
}

TEST(StudySpec, ErrorsNameFileLineKeyValueAndConstraint) {
  EXPECT_EQ(error_of(replaced(kValid, "replicates = 3", "replicates = 3\nreplicate = 2")),
            "s.toml:27: unknown key sweep.replicate: valid keys are elements, cost, noise, replicates, method, start, "
            "pulse_width_s, samples");
  EXPECT_EQ(error_of(replaced(kValid, "seed = 5", "seed = -5")),
            "s.toml:4: study.seed = -5: must be an integer in 0..2^53 - 1");
  EXPECT_EQ(error_of(replaced(kValid, "seed = 5", "seed = 9007199254740993")),  // 2^53 + 1, no double: P361
            "s.toml:4: study.seed = 9007199254740993: must be an integer in 0..2^53 - 1");
  // 2^53 itself is beyond the range the message states, and a float is no seed, as for every integer key (the
  // twenty-eighth pass's adv64 P3 ran seeds 7.0 and 1e3); 2^53 - 1 is one.
  EXPECT_EQ(error_of(replaced(kValid, "seed = 5", "seed = 9007199254740992")),
            "s.toml:4: study.seed = 9007199254740992: must be an integer in 0..2^53 - 1");
  EXPECT_EQ(error_of(replaced(kValid, "seed = 5", "seed = 7.0")),
            "s.toml:4: study.seed = 7.0: must be an integer in 0..2^53 - 1");
  EXPECT_EQ(error_of(replaced(kValid, "seed = 5", "seed = 9007199254740991")), "no error");
  EXPECT_EQ(error_of(replaced(kValid, "pulse_width_s = 0.004", "pulse_width_s = -0.004")),
            "s.toml:10: truth.pulse_width_s = -0.004: must be at least 1e-12 s (narrower is an impulse at any dt >= "
            "1e-9 s)");
  EXPECT_EQ(
      error_of(replaced(kValid, "cost = [\"time\", \"spike-smooth\"]", "cost = [\"time\", \"spiky\"]")),
      "s.toml:24: sweep.cost element 'spiky': must be one of time, spike, spike-smooth, freq-band, freq-ml, modal");
  EXPECT_EQ(error_of(replaced(kValid, "elements = [4, 8]", "elements = [4, 48]")),
            "s.toml:23: sweep.elements element 48: must be in 1..47");  // coarser than N_truth: no inverse crime
  EXPECT_EQ(
      error_of(replaced(kValid, "EI = 1.05", "EI = 2.5")),
      "s.toml:16: starts.near.EI = 2.5: must lie strictly inside the bounds, (1/F, F) with F = fit.bound_factor = 2");
  // A misspelt start key is named before the key it replaces is missed (the twentieth pass: "missing key 'EI'").
  EXPECT_EQ(error_of(replaced(kValid, "EI = 1.05", "EJ = 1.05")).rfind("s.toml:16: unknown key starts.near.EJ", 0), 0u)
      << error_of(replaced(kValid, "EI = 1.05", "EJ = 1.05"));
  EXPECT_EQ(error_of(replaced(kValid, "[fit]", "[fits]")),
            "s.toml:12: unknown table [fits]: valid tables are study, truth, fit, starts, methods, sweep, landscape, "
            "start_distance, outputs");
  EXPECT_EQ(error_of(replaced(kValid, "force_x_m = 0.32", "force_x_m = 0.9")),
            "s.toml:9: truth.force_x_m = 0.9: must lie on the beam, 0 <= x <= l = 0.4573");
  // At the clamp every case failed with exit 0 (the eleventh pass's TF_24): refused on its line.
  EXPECT_NE(error_of(replaced(kValid, "force_x_m = 0.32", "force_x_m = 0.0"))
                .find("s.toml:9: truth.force_x_m = 0: must be a finite position of at least 1e-9 m (at the clamp"),
            std::string::npos)
      << error_of(replaced(kValid, "force_x_m = 0.32", "force_x_m = 0.0"));
  EXPECT_EQ(error_of(replaced(kValid, "method = [\"direct\"]", "method = [\"staged\"]")),
            "s.toml:27: sweep.method element 'staged': must be one of direct");
  EXPECT_EQ(
      error_of(replaced(kValid, "estimate = [\"EI\", \"rho\"]", "estimate = [\"EI\", \"stiffness\"]")).substr(0, 60),
      "s.toml:13: fit.estimate element 'stiffness': must be one of ");
  EXPECT_EQ(
      error_of(replaced(kValid, "name = \"mini\"", "name = \"Mini Study\"")),
      "s.toml:2: study.name = 'Mini Study': must be a non-empty word of a-z, 0-9, '-', '_' (it names results/<name>/)");
  EXPECT_EQ(error_of("[study]\nname = 'x'\nquestion = 'q'\nseed = 1\n"), "s.toml:1: missing table [truth]");
  // A method's or start's name is a value of the tables' rows: a comma in one broke them (the twenty-second pass's P3).
  EXPECT_NE(error_of(replaced(kValid, "[methods.direct]", "[methods.'a,b']")).find("[methods.'a,b']: its name must be"),
            std::string::npos)
      << error_of(replaced(kValid, "[methods.direct]", "[methods.'a,b']"));
  EXPECT_NE(error_of(replaced(kValid, "[starts.near]", "[starts.'']")).find("[starts.'']: its name must be"),
            std::string::npos)
      << error_of(replaced(kValid, "[starts.near]", "[starts.'']"));
  // max_spikes bounds spikes = "auto" only: beside a given count it was read by nothing (the twenty-first pass's P8).
  EXPECT_NE(error_of(replaced(kValid, "[fit]", "[fit]\nspikes = 3\nmax_spikes = 2"))
                .find("s.toml:14: fit.max_spikes = 2: is read only with spikes = \"auto\""),
            std::string::npos)
      << error_of(replaced(kValid, "[fit]", "[fit]\nspikes = 3\nmax_spikes = 2"));
  EXPECT_EQ(error_of(std::string(kValid) + "\n[landscape]\ncost = [\"time\"]\npairs = [[\"EI\", \"gamma\"]]\n"),
            "s.toml:32: landscape.pairs element [...]: 'gamma' is not in fit.estimate");
  EXPECT_EQ(error_of(replaced(kValid, "[methods.direct]", "[methods.direct]\nwindow = \"kaiser\"")).substr(0, 75),
            "s.toml:20: methods.direct.window = 'kaiser': must be one of rectangular, ha");
  EXPECT_EQ(error_of(replaced(kValid, "[methods.direct]", "[methods.direct]\neps2_factor = 0")),
            "s.toml:20: methods.direct.eps2_factor = 0: must be in (0, 1e6]");
  // A method's override that none of its costs reads (the time cost has no window): refused, not ignored (the second
  // pass's N459, N460).
  EXPECT_EQ(error_of(replaced(replaced(kValid, "[methods.direct]", "[methods.direct]\nwindow = \"hann\""),
                              "cost = [\"time\", \"spike-smooth\"]", "cost = [\"time\"]")),
            "s.toml:20: methods.direct.window is read by the DFT costs (spike, spike-smooth, freq-band); this method "
            "runs only time");
  EXPECT_EQ(error_of(replaced(kValid, "[methods.direct]", "[methods.direct]\nwindow = \"hann\"")), "no error");
  // The [fit] table's in a study of the time cost alone (the fourth pass's Q534), and fine beside a spike cost.
  EXPECT_EQ(error_of(replaced(replaced(kValid, "[fit]", "[fit]\nfrequency_weight = \"relative\""),
                              "cost = [\"time\", \"spike-smooth\"]", "cost = [\"time\"]")),
            "s.toml:13: fit.frequency_weight is read by the spike costs (spike, spike-smooth); this study runs only "
            "time");
  EXPECT_EQ(error_of(replaced(kValid, "[fit]", "[fit]\nfrequency_weight = \"relative\"")), "no error");
  EXPECT_EQ(error_of(replaced(replaced(kValid, "[fit]", "[fit]\nmax_frequency_hz = 300.0"),
                              "cost = [\"time\", \"spike-smooth\"]", "cost = [\"time\"]")),
            "s.toml:13: fit.max_frequency_hz is read by the spike costs, modal and freq-band; this study runs only "
            "time");
  // The band lies below the truth record's Nyquist frequency, 500 Hz at the default dt (the twenty-fourth pass's
  // adv56 P4: the spike costs took aliases for modes).
  EXPECT_EQ(error_of(replaced(kValid, "[fit]", "[fit]\nmax_frequency_hz = 800.0")),
            "s.toml:13: fit.max_frequency_hz = 800: must be at most the truth record's Nyquist frequency 500 Hz "
            "(truth.dt_s = 0.001)");
  EXPECT_EQ(error_of(replaced(kValid, "[fit]", "[fit]\nmax_frequency_hz = 500.0")), "no error");
  EXPECT_EQ(error_of(std::string(kValid) + "\n[landscape]\ncost = [\"time\"]\nnoise = [0.0, 1.5]\n"),
            "s.toml:32: landscape.noise element 1.5: must be in [0, 1] (a fraction of the clean RMS)");
  EXPECT_EQ(error_of(std::string(kValid) + "\n[landscape]\ncost = [\"time\"]\nzoom_range_factor = 1.03\n"),
            "s.toml:32: landscape.zoom_range_factor = 1.03: needs landscape.pairs (the grids it zooms)");
  // A path the file system refuses (longer than PATH_MAX) is a missing file, not a filesystem_error: a fuzz finding.
  const std::string long_name(5000, 'd');
  EXPECT_EQ(error_of(replaced(kValid, "beam = \"banks-aluminium\"", "beam = \"" + long_name + "\"")).substr(0, 27),
            "s.toml:7: truth.beam = 'ddd");
  EXPECT_NE(error_of(replaced(kValid, "beam = \"banks-aluminium\"", "beam = \"" + long_name + "\""))
                .find("must be a preset (banks-aluminium, thick-steel) or an existing beam TOML file"),
            std::string::npos);
  EXPECT_EQ(error_of("[study\n"),
            "s.toml:1: TOML syntax error: Error while parsing table header: expected ']', saw '\\n'");
}

TEST(StudyPlan, IdsAreStableSeedsDeriveFromThemAndNoiseIsShared) {
  const StudySpec s = parse_study(kValid, "s.toml", ".");
  const Plan plan = make_plan(s);
  // 2 N x 2 costs x (1 noise-free + 3 noisy replicates): a noise-free case runs once; plus a unit per N that
  // computes the Galerkin frequencies of the truth beam.
  ASSERT_EQ(plan.units.size(), 18u);
  EXPECT_EQ(plan.units.back().kind, UnitKind::Frequencies);
  ASSERT_EQ(plan.truths.size(), 1u);
  std::set<std::string> ids;
  for (const auto& u : plan.units) ids.insert(u.id);
  EXPECT_EQ(ids.size(), plan.units.size());
  // Adding a cost and an N leaves every existing id and seed as it was.
  const Plan bigger = make_plan(parse_study(replaced(replaced(kValid, "cost = [\"time\", \"spike-smooth\"]",
                                                              "cost = [\"spike\", \"time\", \"spike-smooth\"]"),
                                                     "elements = [4, 8]", "elements = [2, 4, 8]"),
                                            "s.toml", "."));
  std::map<std::string, std::uint64_t> seeds;
  for (const auto& u : bigger.units) seeds[u.id] = u.seed;
  for (const auto& u : plan.units) {
    ASSERT_TRUE(seeds.count(u.id)) << u.canonical;
    EXPECT_EQ(seeds[u.id], u.seed);
  }
  // Every cost and N of one (noise, replicate) sees the same noise; replicates see different noise.
  std::map<std::pair<double, int>, std::set<std::uint64_t>> noise;
  for (const auto& u : plan.units)
    if (u.kind == UnitKind::Case) noise[{u.noise, u.replicate}].insert(u.noise_seed);
  for (const auto& [k, v] : noise) EXPECT_EQ(v.size(), 1u);
  const std::pair<double, int> first{0.01, 0}, second{0.01, 1};
  EXPECT_NE(*noise[first].begin(), *noise[second].begin());
  // A different study seed changes seeds but not ids.
  const Plan reseeded = make_plan(parse_study(replaced(kValid, "seed = 5", "seed = 6"), "s.toml", "."));
  EXPECT_EQ(reseeded.units[3].id, plan.units[3].id);
  EXPECT_NE(reseeded.units[3].seed, plan.units[3].seed);
}

TEST(StudySpec, TheRecordsNoiseColourAndAMethodsAssumedNoiseAreReadAndNamedInTheIds) {
  // [truth] noise_model colours every record; a method's noise_model ("truth": the records' own) is what the time
  // and freq-ml costs assume. Bad values name the line; a method's model with no cost that reads it is refused.
  const std::string coloured =
      replaced(replaced(replaced(kValid, "pulse_width_s = 0.004", "pulse_width_s = 0.004\nnoise_model = \"ar:0.9\""),
                        "strategy = \"direct\"", "strategy = \"direct\"\nnoise_model = \"truth\""),
               "cost = [\"time\", \"spike-smooth\"]", "cost = [\"time\", \"freq-ml\"]");
  const StudySpec s = parse_study(coloured, "s.toml", ".");
  EXPECT_EQ(s.truth.noise_model, "ar:0.9");
  EXPECT_EQ(s.methods.at(0).noise_model, "truth");
  EXPECT_EQ(error_of(replaced(kValid, "pulse_width_s = 0.004", "pulse_width_s = 0.004\nnoise_model = \"ar:1.1\"")),
            "s.toml:11: truth.noise_model = 'ar:1.1': not stationary: a root of z^p - a1 z^(p-1) - ... has modulus "
            "1.1 (must be below 1 - 1e-6: nearer 1, the process's variance and correlation time exceed any record)");
  EXPECT_EQ(
      error_of(replaced(replaced(kValid, "strategy = \"direct\"", "strategy = \"direct\"\nnoise_model = \"ar:0.5\""),
                        "cost = [\"time\", \"spike-smooth\"]", "cost = [\"spike-smooth\"]")),
      "s.toml:21: methods.direct.noise_model is read by the time and freq-ml costs; this method runs only "
      "spike-smooth");
  EXPECT_EQ(error_of(replaced(kValid, "strategy = \"direct\"", "strategy = \"direct\"\nnoise_model = \"ar:0.5\"")),
            "s.toml:21: methods.direct.noise_model is read by the time and freq-ml costs; this method also runs "
            "spike-smooth, whose fits would be white under its name: give that cost a method of its own");
  // White records keep the ids they had before the key existed; a colour or an assumed model changes them.
  const Plan white = make_plan(parse_study(kValid, "s.toml", "."));
  const Plan explicit_white = make_plan(parse_study(
      replaced(kValid, "pulse_width_s = 0.004", "pulse_width_s = 0.004\nnoise_model = \"white\""), "s.toml", "."));
  const Plan ar = make_plan(s);
  ASSERT_EQ(white.units.size(), ar.units.size());
  for (std::size_t i = 0; i < white.units.size(); ++i) {
    EXPECT_EQ(white.units[i].id, explicit_white.units[i].id);
    if (white.units[i].kind == UnitKind::Case) {
      EXPECT_NE(white.units[i].id, ar.units[i].id);
    }
  }
}

TEST(StudySpec, AMeasuredForceItsNoiseAndTheErrorsInVariablesMethodAreReadAndRefusedWhereTheyCannotApply) {
  const std::string force = replaced(
      replaced(
          replaced(kValid, "pulse_width_s = 0.004", "pulse_width_s = 0.004\nexcitation = \"force\"\nforce_noise = 0.2"),
          "strategy = \"direct\"", "strategy = \"direct\"\nerrors_in_variables = true"),
      "cost = [\"time\", \"spike-smooth\"]", "cost = [\"freq-ml\"]");
  const StudySpec s = parse_study(force, "s.toml", ".");
  EXPECT_EQ(s.truth.experiment.excitation, "force");
  EXPECT_EQ(s.truth.force_noise, 0.2);
  EXPECT_TRUE(s.methods.at(0).errors_in_variables);
  // The force's noise and the method's form enter the units' ids.
  const Plan eiv = make_plan(s);
  const Plan oe = make_plan(parse_study(replaced(force, "errors_in_variables = true", ""), "s.toml", "."));
  for (std::size_t i = 0; i < eiv.units.size(); ++i)
    if (eiv.units[i].kind == UnitKind::Case) {
      EXPECT_NE(eiv.units[i].id, oe.units[i].id);
    }
  EXPECT_EQ(error_of(replaced(kValid, "pulse_width_s = 0.004", "pulse_width_s = 0.004\nforce_noise = 0.2")),
            "s.toml:11: truth.force_noise = 0.2: is noise on a measured force channel: needs excitation = 'force' "
            "(excitation is 'pulse')");
  EXPECT_EQ(error_of(replaced(kValid, "strategy = \"direct\"", "strategy = \"direct\"\nerrors_in_variables = true")),
            "s.toml:21: methods.direct.errors_in_variables = true: weighs the force channel's noise: needs [truth] "
            "excitation = 'force' and force_noise > 0");
  EXPECT_EQ(error_of(replaced(force, "cost = [\"freq-ml\"]", "cost = [\"freq-ml\", \"time\"]")),
            "s.toml:23: methods.direct.errors_in_variables is freq-ml's form; this method also runs time");
  EXPECT_NE(error_of(force + "\n[outputs]\nefficiency = true\n").find("compares with the bound for a known force"),
            std::string::npos);
  // The errors-in-variables weights need the response's noise given: with an estimated one every case failed at run
  // time (the adversarial pass's P6).
  EXPECT_NE(
      error_of(replaced(force, "errors_in_variables = true", "errors_in_variables = true\nnoise_model = \"estimated\""))
          .find("with noise_model = 'estimated' it has none"),
      std::string::npos);
}

TEST(StudySpec, AModalDampingTruthIsReadNamedInTheIdsAndRefusedInAControl) {
  const std::string damped =
      replaced(kValid, "pulse_width_s = 0.004", "pulse_width_s = 0.004\nmodal_damping_ratio = 0.002");
  EXPECT_EQ(parse_study(damped, "s.toml", ".").truth.modal_damping_ratio, 0.002);
  const Plan with = make_plan(parse_study(damped, "s.toml", ".")),
             without = make_plan(parse_study(kValid, "s.toml", "."));
  ASSERT_EQ(with.truths.size(), without.truths.size());
  EXPECT_NE(with.truths.front().id, without.truths.front().id);
  EXPECT_EQ(
      error_of(replaced(damped, "beam = \"banks-aluminium\"", "beam = \"banks-aluminium\"\ncontrol = true")),
      "s.toml:12: truth.modal_damping_ratio = 0.002: gives the truth a damping law no fitted model has; control = "
      "true fits the truth's own model");
  EXPECT_NE(error_of(replaced(kValid, "pulse_width_s = 0.004", "pulse_width_s = 0.004\nmodal_damping_ratio = 0.6"))
                .find("must be in [0, 0.5]"),
            std::string::npos);
}

TEST(StudySpec, AFiniteBandwidthSensorIsReadNamedInTheIdsAndRefusedWhereItCannotBe) {
  const std::string sensed = replaced(kValid, "pulse_width_s = 0.004",
                                      "pulse_width_s = 0.004\nsensor_bandwidth_hz = 200\nsensor_filter_order = 6");
  const StudySpec s = parse_study(sensed, "s.toml", ".");
  EXPECT_EQ(s.truth.sensor.cutoff_hz, 200);
  EXPECT_EQ(s.truth.sensor.order, 6);
  EXPECT_NE(make_plan(s).truths.front().id, make_plan(parse_study(kValid, "s.toml", ".")).truths.front().id);
  // At dt = 1 ms the filter runs at 16 kHz: its cut-off must be below 2 kHz.
  EXPECT_EQ(error_of(replaced(kValid, "pulse_width_s = 0.004", "pulse_width_s = 0.004\nsensor_bandwidth_hz = 2500")),
            "s.toml:11: truth.sensor_bandwidth_hz = 2500: must be below 2000 Hz (a quarter of the Nyquist frequency of "
            "the 16x faster record the filter runs on, where its digital form follows the analog one)");
  EXPECT_NE(error_of(replaced(sensed, "beam = \"banks-aluminium\"", "beam = \"banks-aluminium\"\ncontrol = true"))
                .find("filters the truth's output as the fitted model does only with a method's sensor_in_model"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(sensed, "samples = 256", "samples = 2097152")).find("16 times finer: at most 1048576"),
            std::string::npos);
  // The filter in a method's fitted model: read, in the cases' ids, and refused without a filter to put there.
  const StudySpec known = parse_study(
      replaced(sensed, "strategy = \"direct\"", "strategy = \"direct\"\nsensor_in_model = true"), "s.toml", ".");
  EXPECT_TRUE(known.methods.at(0).sensor_in_model);
  EXPECT_NE(make_plan(known).units.front().id, make_plan(s).units.front().id);
  EXPECT_EQ(error_of(replaced(kValid, "strategy = \"direct\"", "strategy = \"direct\"\nsensor_in_model = true")),
            "s.toml:21: methods.direct.sensor_in_model = true: puts the truth's sensor filter in the fitted model: "
            "needs [truth] sensor_bandwidth_hz > 0");
  // An order without a cut-off would be an unread key (the adversarial pass's P7).
  EXPECT_NE(error_of(replaced(kValid, "pulse_width_s = 0.004", "pulse_width_s = 0.004\nsensor_filter_order = 4"))
                .find("needs sensor_bandwidth_hz > 0"),
            std::string::npos);
}

// A truth beam read from a file enters the units' identity by its values, not only its path: editing the file changes
// every unit's id (so the store recomputes them instead of reusing records of the old beam), rewriting it unchanged
// keeps them; a preset's units keep ids that name the preset alone.
TEST(StudyPlan, EditingATruthBeamFileChangesTheUnitIds) {
  namespace fs = std::filesystem;
  const fs::path folder = fs::temp_directory_path() / ("beamid-plan-beam-" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const std::string beam = R"([beam]
l = 0.4573
rho = 0.093
rho_r2 = 1.984e-08
kAG = 736300.0
EI = 0.491
gamma = 0.013
cDI = 6.49e-06
kAcs = 9.73
m = 0.05
c = 0.0125
J_o = 5.208e-06
)";
  const auto write_beam = [&](const std::string& text) { std::ofstream(folder / "b.toml") << text; };
  const std::string study = replaced(kValid, "beam = \"banks-aluminium\"", "beam = \"b.toml\"");
  const auto ids = [&] {
    std::vector<std::string> out;
    const Plan plan = make_plan(parse_study(study, (folder / "s.toml").string(), folder.string()));
    for (const auto& u : plan.truths) out.push_back(u.id);
    for (const auto& u : plan.units) out.push_back(u.id);
    return out;
  };
  write_beam(beam);
  const std::vector<std::string> first = ids();
  write_beam(beam);
  EXPECT_EQ(ids(), first);
  write_beam(replaced(beam, "EI = 0.491", "EI = 0.5"));
  const std::vector<std::string> edited = ids();
  ASSERT_EQ(edited.size(), first.size());
  for (std::size_t i = 0; i < first.size(); ++i) EXPECT_NE(edited[i], first[i]) << i;
  fs::remove_all(folder);
  // Presets: the canonical text names the preset, as before (the committed studies' ids stand).
  const Plan preset = make_plan(parse_study(kValid, "s.toml", "."));
  EXPECT_EQ(preset.truths[0].canonical.rfind("truth;beam=banks-aluminium;N_truth=", 0), 0u)
      << preset.truths[0].canonical;
}

TEST(StudySpec, StartDistanceRunsAreCostSlashMethod) {
  const std::string base = std::string(kValid) + "\n[start_distance]\noffsets = [0.001, 0.01]\ndirections = 4\n";
  EXPECT_EQ(error_of(base + "runs = [\"time-direct\"]\n"),
            "s.toml:33: start_distance.runs element 'time-direct': must be \"cost/method\", e.g. \"time/direct\"");
  EXPECT_EQ(error_of(base + "runs = [\"time/staged\"]\n"),
            "s.toml:33: start_distance.runs element 'time/staged': method 'staged' must be one of the "
            "[methods.NAME] tables (direct)");
  EXPECT_EQ(error_of(base + "runs = [\"spiky/direct\"]\n"),
            "s.toml:33: start_distance.runs element 'spiky/direct': cost 'spiky' must be one of time, spike, "
            "spike-smooth, freq-band, freq-ml, modal");
  EXPECT_EQ(error_of(replaced(base, "[0.001, 0.01]", "[0.01, 0.001]") + "runs = [\"time/direct\"]\n"),
            "s.toml:31: start_distance.offsets = [...]: must be in increasing order");
  EXPECT_EQ(error_of(replaced(kValid, "strategy = \"direct\"", "strategy = \"direct\"\nrefine = \"time\"")),
            "s.toml:21: methods.direct.refine = 'time': applies to strategy = 'hybrid' only");
}

TEST(StudyPlan, StartDistanceUnitsShareDirectionsAndTheRecord) {
  const StudySpec s = parse_study(std::string(kValid) +
                                      "\n[start_distance]\noffsets = [0.001, 0.01]\ndirections = 4\nnoise = 0.01\n"
                                      "runs = [\"time/direct\", \"spike-smooth/direct\"]\n",
                                  "s.toml", ".");
  const Plan plan = make_plan(s);
  // Per run: the fit from the truth plus 2 offsets x 4 directions.
  std::vector<const Unit*> starts;
  for (const auto& u : plan.units)
    if (u.kind == UnitKind::Start) starts.push_back(&u);
  ASSERT_EQ(starts.size(), 2u * (1 + 2 * 4));
  std::set<std::string> ids;
  std::set<std::uint64_t> noise;
  for (const Unit* u : starts) ids.insert(u->id), noise.insert(u->noise_seed);
  EXPECT_EQ(ids.size(), starts.size());
  EXPECT_EQ(noise.size(), 1u);  // one record for every run, offset and direction (paired comparisons)
  EXPECT_EQ(starts.front()->index, -1);
  EXPECT_EQ(starts.front()->offset, 0.0);
  // The start units come after the cases and leave their ids alone.
  const Plan without = make_plan(parse_study(kValid, "s.toml", "."));
  for (std::size_t i = 0; i + 2 < without.units.size(); ++i) EXPECT_EQ(without.units[i].id, plan.units[i].id);
}

TEST(StudyPlan, StartDistanceRecordsEachHaveTheirOwnNoiseAndReference) {
  const std::string text = std::string(kValid) +
                           "\n[start_distance]\noffsets = [0.001, 0.01]\ndirections = 2\nnoise = 0.01\nrecords = 3\n"
                           "runs = [\"time/direct\"]\n";
  const Plan plan = make_plan(parse_study(text, "s.toml", "."));
  std::vector<const Unit*> starts;
  for (const auto& u : plan.units)
    if (u.kind == UnitKind::Start) starts.push_back(&u);
  // Per record: the fit from the truth plus 2 offsets x 2 directions.
  ASSERT_EQ(starts.size(), 3u * (1 + 2 * 2));
  std::map<int, std::set<std::uint64_t>> noise;
  std::map<int, int> references;
  std::set<std::string> ids;
  for (const Unit* u : starts) {
    noise[u->replicate].insert(u->noise_seed);
    references[u->replicate] += u->index < 0 ? 1 : 0;
    ids.insert(u->id);
  }
  EXPECT_EQ(ids.size(), starts.size());
  ASSERT_EQ(noise.size(), 3u);
  for (const auto& [record, seeds] : noise) {
    EXPECT_EQ(seeds.size(), 1u);          // one record for every start of it
    EXPECT_EQ(references.at(record), 1);  // and its own reference minimum
  }
  EXPECT_NE(*noise[0].begin(), *noise[1].begin());
  // Record r is the sweep's replicate-r draw at that noise: the cases of kValid (noise 0.01, replicate 0) see
  // record 0.
  for (const auto& u : plan.units)
    if (u.kind == UnitKind::Case && u.noise == 0.01 && u.replicate == 0) EXPECT_EQ(u.noise_seed, *noise[0].begin());
  // Noise-free records are all one record.
  EXPECT_EQ(error_of(replaced(text, "noise = 0.01\nrecords", "noise = 0\nrecords")),
            "s.toml:34: start_distance.records = 3: must be 1 when noise = 0 (noise-free records are all the same "
            "record)");
}

TEST(StudyPlan, StartDistanceRecordsBringTheirBoundOnce) {
  const auto bounds = [](const std::string& text) {
    std::vector<std::pair<double, int>> out;
    for (const auto& u : make_plan(parse_study(text, "s.toml", ".")).units)
      if (u.kind == UnitKind::Bound) out.emplace_back(u.noise, u.elements);
    return out;
  };
  const std::string starts =
      "\n[start_distance]\nelements = 8\noffsets = [0.01]\ndirections = 1\nnoise = 0.01\n"
      "runs = [\"time/direct\"]\n";
  // No efficiency output and one record: no bound.
  EXPECT_TRUE(bounds(std::string(kValid) + starts).empty());
  // Several records: the start distance's experiment, at its noise and N.
  EXPECT_EQ(bounds(std::string(kValid) + starts + "records = 2\n"), (std::vector<std::pair<double, int>>{{0.01, 8}}));
  // With the sweep's bounds as well, that setting once, after the sweep's own (noise 0.01 at N = 4 and 8).
  EXPECT_EQ(bounds(std::string(kValid) + starts + "records = 2\n[outputs]\nefficiency = true\n"),
            (std::vector<std::pair<double, int>>{{0.01, 4}, {0.01, 8}}));
}

TEST(StudyPlan, ShardsPartitionTheUnits) {
  const Plan plan = make_plan(parse_study(kValid, "s.toml", "."));
  std::multiset<std::string> seen;
  for (int k = 1; k <= 3; ++k)
    for (const Unit* u : shard(plan.units, k, 3)) seen.insert(u->id);
  EXPECT_EQ(seen.size(), plan.units.size());
  for (const auto& u : plan.units) EXPECT_EQ(seen.count(u.id), 1u);
}

}  // namespace
}  // namespace beamid::study
