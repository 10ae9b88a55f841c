// The typed requests that compute from a beam model or a record alone (api/model_requests.h, api/record_requests.h):
// filled in C++, they give the physics the command line gives, and they refuse what the command line refuses, in its
// one-line form, including what only the command line's flag parser checked before (N's range).
#include "api/model_requests.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "api/record_requests.h"
#include "core/errors.h"
#include "signal/noise.h"

namespace beamid::api {
namespace {

// The message a computation refuses its request with ("" when it does not).
template <typename Compute>
std::string refusal(Compute compute) {
  try {
    compute();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ModesRequest, ExactAndGalerkinFrequenciesOfTheThinBeam) {
  std::ostringstream warnings;
  ModesRequest exact;
  exact.beam = model::preset("banks-aluminium");
  exact.exact = true;
  const ModesResult e = compute_modes(exact, warnings);
  ASSERT_EQ(e.frequency_hz.size(), 4u);
  // The exact Timoshenko frequencies with the tip body (README: 2.464, 26.50, 81.67, 164.0 Hz to 4 digits).
  EXPECT_NEAR(e.frequency_hz[0], 2.464, 5e-4);
  EXPECT_NEAR(e.frequency_hz[3], 164.0, 0.05);
  ModesRequest galerkin = exact;
  galerkin.exact = false;
  galerkin.elements = 16;
  galerkin.count = 4;
  const ModesResult g = compute_modes(galerkin, warnings);
  ASSERT_EQ(g.frequency_hz.size(), 4u);
  // The damped Galerkin modes at N = 16 against the undamped exact ones: the first two agree to 1e-4 (measured
  // 1.1e-7 and 6.6e-5: discretisation error, growing with the mode number, plus the damping's zeta^2 / 2 < 1.1e-6);
  // the third and fourth are 7.0e-4 and 3.0e-3 high at this N, so they are only checked to lie above the exact ones, as
  // a conforming Galerkin approximation's undamped frequencies must (Rayleigh-Ritz: upper bounds).
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(g.frequency_hz[k] / e.frequency_hz[k], 1, 1e-4) << "mode " << k + 1;
  for (int k = 2; k < 4; ++k) EXPECT_GT(g.frequency_hz[k], e.frequency_hz[k]) << "mode " << k + 1;
}

TEST(ModelRunRequest, RefusesWhatOnlyTheFlagParserCheckedBefore) {
  std::ostringstream warnings;
  ModelRunRequest run;
  run.beam = model::preset("thick-steel");
  run.elements = 0;
  EXPECT_EQ(refusal([&] { compute_system(run, warnings); }),
            "beamid system: --elements = '0': must be an integer in 1..400");
  run.elements = 8;
  run.experiment.sensor_x_m = {0.5};  // the thick beam is 0.3 m long
  EXPECT_EQ(refusal([&] { compute_system(run, warnings); }),
            "beamid system: --sensor-x = '0.5': must lie on the beam, 0 <= x <= l = 0.3");
  SimulateRequest simulate;
  simulate.run.beam = model::preset("thick-steel");
  simulate.run.elements = 8;
  simulate.seed = 3;
  EXPECT_EQ(refusal([&] { compute_simulate(simulate, warnings); }),
            "beamid simulate: --seed = '3': seeds the noise: give --noise-level too");
  CrbRequest crb;
  crb.run.beam = model::preset("thick-steel");
  crb.run.elements = 8;
  crb.estimate = {"EI"};
  EXPECT_EQ(refusal([&] { compute_crb(crb, warnings); }),
            "beamid crb: give one of --noise-sd S (absolute) and --noise-level L (fraction of the RMS)");
}

// banks-aluminium's 4 ms tip pulse at N elements over `samples` samples, noise-free, as a record.
io::TimeSeries simulated_record(int elements, int samples) {
  std::ostringstream warnings;
  SimulateRequest simulate;
  simulate.run.beam = model::preset("banks-aluminium");
  simulate.run.elements = elements;
  simulate.run.experiment.samples = samples;
  simulate.run.experiment.pulse_width_s = 0.004;
  const SimulateResult s = compute_simulate(simulate, warnings);
  io::TimeSeries record;
  record.path = "<simulated>";
  record.dt_s = s.run.experiment.dt_s;
  record.values = s.y;
  return record;
}

TEST(RecordRequests, ASpikesDecayRateIsNeverNegative) {
  // The thin beam at N = 6, 1024 samples after the 4 ms pulse, noise-free: the three-bin estimate of spike 2's decay
  // rate came out -0.098 1/s, the neighbours' leakage on a 1 s record, where the mode decays at 0.255 1/s (the
  // twenty-second pass's P4). A passive beam's modes decay: a rate is positive or NaN, never negative.
  const io::TimeSeries record = simulated_record(6, 1024);
  SpikesRequest spikes;
  spikes.spikes.count = 4;
  const SpikesResult p = compute_spikes(spikes, record);
  ASSERT_GE(p.picks.size(), 2u);
  for (const auto& pick : p.picks) {
    const double rate = p.subbin(pick.bin).decay_rate_1_s;
    EXPECT_TRUE(std::isnan(rate) || rate > 0) << pick.frequency_hz << " Hz: " << rate;
  }
}

TEST(RecordRequests, SpikesAndModalIdFindTheModesOfASimulatedRecord) {
  std::ostringstream warnings;
  const io::TimeSeries record = simulated_record(8, simulation::Experiment().samples);
  ModesRequest modes;
  modes.beam = model::preset("banks-aluminium");
  modes.elements = 8;
  modes.count = 2;
  const ModesResult m = compute_modes(modes, warnings);

  SpikesRequest spikes;  // the defaults of a measured record: detrended, the offset's leakage rejected
  spikes.spikes.count = 2;
  const SpikesResult p = compute_spikes(spikes, record);
  ASSERT_EQ(p.picks.size(), 2u);
  // A bin is df = 1/(4096 dt) = 0.244 Hz wide: the picked bins lie within one bin of the model's first two modes.
  const double df = p.spectrum.df_hz();
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(p.picks[k].frequency_hz, m.frequency_hz[k], df) << "spike " << k + 1;

  io::TimeSeries decay = record;  // the free decay after the 4 ms pulse, as modal-id wants it (--start)
  decay.values.erase(decay.values.begin(), decay.values.begin() + 8);
  ModalIdRequest pencil;
  pencil.modes = 2;
  pencil.max_frequency_hz = 60;
  const ModalIdResult id = compute_modal_id(pencil, decay);
  ASSERT_EQ(id.modes.size(), 2u);
  // A noise-free free decay of the model itself: the pencil returns its damped poles to round-off and the modes
  // above the band's edge (1e-6 leaves orders of magnitude; a wrong window or step moves them by 1e-3 or more).
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(id.modes[k].frequency_hz / m.frequency_hz[k], 1, 1e-6) << k;
  pencil.max_frequency_hz = -1;
  EXPECT_EQ(refusal([&] { compute_modal_id(pencil, decay); }),
            "beamid modal-id: --max-frequency = '-1': must exceed --min-frequency = '0'");
  // A band above the Nyquist frequency (500 Hz here) holds nothing: refused, not an empty table (the twelfth pass's
  // P11).
  pencil.min_frequency_hz = 600;
  pencil.max_frequency_hz = 700;
  EXPECT_NE(refusal([&] {
              compute_modal_id(pencil, decay);
            }).find("--min-frequency = '600': must be below the Nyquist frequency"),
            std::string::npos);
  // One sample at 50 times the record's largest is a glitch, said as one rather than as a lead-in to cut away (P6).
  io::TimeSeries glitch = decay;
  double peak = 0;
  for (double v : glitch.values) peak = std::max(peak, std::abs(v));
  glitch.values[1000] = 50 * peak;
  EXPECT_NE(lead_in_note(glitch, "the pencil").find("sample 1001 (t = 1 s) is 50 times every other sample: a glitch"),
            std::string::npos)
      << lead_in_note(glitch, "the pencil");
  EXPECT_EQ(lead_in_note(decay, "the pencil"), "");  // the decay itself: largest at its start
}

TEST(RecordRequests, BeyondEightPicksTheLargestAreStillMeasured) {
  // The twenty-eighth pass's adv65 P5: with 18 picks on the steel record one pencil for all failed at a noise peak,
  // and every pick was left NaN (its clear bending modes too), each given that failure at another pick. Three decaying
  // modes and 1 % noise, 8192 samples at 1 kHz, 16 picks by prominence (most of them noise peaks): the three modes are
  // measured (to 1e-3 Hz: 3 bins of 0.12 Hz search, noise sd 1e-2 over 8 s), the picks not measured alone are named
  // once with the reason.
  io::TimeSeries record;
  record.path = "<three modes>";
  record.dt_s = 1e-3;
  const std::vector<double> noise = signal::gaussian_deviates(7, 8192);
  for (int i = 0; i < 8192; ++i) {
    const double t = i * 1e-3, pi = std::numbers::pi;
    record.values.push_back(
        std::exp(-0.3 * t) * std::sin(2 * pi * 6.6 * t) + 0.5 * std::exp(-0.8 * t) * std::sin(2 * pi * 41.4 * t) +
        0.3 * std::exp(-1.5 * t) * std::sin(2 * pi * 116.9 * t) + 1e-2 * noise[static_cast<std::size_t>(i)]);
  }
  SpikesRequest spikes;
  spikes.spikes.count = 16;
  spikes.spikes.rule = "prominence";
  const SpikesResult p = compute_spikes(spikes, record);
  ASSERT_EQ(p.measured.size(), p.picks.size());
  for (const double mode : {6.6, 41.4, 116.9}) {
    bool measured = false;
    for (const auto& m : p.measured) measured |= std::abs(m.mode.frequency_hz - mode) < 1e-3 * mode;
    EXPECT_TRUE(measured) << mode << " Hz: " << p.measured_note;
  }
  EXPECT_NE(p.measured_note.find("were not measured: one pencil for all picks failed"), std::string::npos)
      << p.measured_note;
}

TEST(RecordRequests, EachSpikeGetsItsOwnMeasuredPoleOrNone) {
  // The ninth pass's N_f1: a 48 Hz decay and a steady 50 Hz sine (amplitude 0.3), 4096 samples at 1 kHz. The 50.05 Hz
  // spike was measured at 48.000 Hz, the stronger pole within 5 % of it; searched within three bins (0.73 Hz), each
  // spike gets its own pole, 48 and 50 Hz to round-off (noise-free).
  io::TimeSeries record;
  record.path = "<two tones>";
  record.dt_s = 1e-3;
  for (int i = 0; i < 4096; ++i) {
    const double t = i * 1e-3;
    record.values.push_back(std::exp(-1.5 * t) * std::sin(2 * std::numbers::pi * 48 * t) +
                            0.3 * std::sin(2 * std::numbers::pi * 50 * t));
  }
  SpikesRequest spikes;
  spikes.spikes.count = 2;
  const SpikesResult p = compute_spikes(spikes, record);
  ASSERT_EQ(p.measured.size(), 2u);
  EXPECT_NEAR(p.measured[0].mode.frequency_hz, std::hypot(48.0, 1.5 / (2 * std::numbers::pi)), 1e-6);
  EXPECT_NEAR(p.measured[1].mode.frequency_hz, 50.0, 1e-6);
}

TEST(RecordRequests, ModalIdSaysWhenAModeSplitsIntoTwoClosePoles) {
  // A strip's first mode read 9.406 and 9.421 Hz as two poles (its frequency changes with its amplitude) and
  // nothing said so (issue 31): two lightly damped poles 0.16 % apart are named with their distance; 10 % apart,
  // they are two modes and nothing is said (the note covers up to 5 %).
  signal::PencilOptions o;
  o.modes = 2;
  const auto mode = [](double f) {
    signal::IdentifiedMode m;
    m.frequency_hz = f;
    m.damping_ratio = 0.003;
    m.amplitude = 1;
    const double w = 2 * std::numbers::pi * f;  // the pole, which says it decays (not a steady line)
    m.lambda = {-m.damping_ratio * w, w * std::sqrt(1 - m.damping_ratio * m.damping_ratio)};
    return m;
  };
  const auto notes = modal_id_notes({mode(9.406), mode(9.421)}, {}, o, 10);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("9.406 and 9.421 Hz are 0.16 % apart"), std::string::npos) << notes[0];
  EXPECT_TRUE(modal_id_notes({mode(9.406), mode(10.4)}, {}, o, 10).empty());
  // The ninth pass's d1: one drifting mode's poles 2.6 % apart are said too.
  EXPECT_EQ(modal_id_notes({mode(35.89), mode(36.84)}, {}, o, 10).size(), 1u);
}

}  // namespace
}  // namespace beamid::api
