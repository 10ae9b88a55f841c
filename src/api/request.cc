#include "api/request.h"

#include <algorithm>
#include <cctype>
#include <utility>

#include "core/errors.h"

namespace beamid::api {

namespace {

// The lower layers name an option by its field ("sensor_x_m = 0.5: must lie on the beam"), which is also the study
// file's key; a command's user typed a flag, and was shown the field (the fifth pass's R258-R263, R409). The fields
// that validation reports beside the flag that sets each.
constexpr std::pair<const char*, const char*> kFlagOfField[] = {
    {"sensor_x_m", "sensor-x"},
    {"force_x_m", "force-x"},
    {"force_amplitude_N", "force-amplitude"},
    {"pulse_width_s", "pulse-width"},
    {"dt_s", "dt"},
    {"min_frequency_hz", "min-frequency"},
    {"max_frequency_hz", "max-frequency"},
    {"spikes", "spikes"},
    {"spike_rule", "spike-rule"},
    {"mode_weight", "mode-weight"},
    {"window", "window"},
    {"max_evaluations", "max-evaluations"},
    {"optimizer", "optimizer"},
    {"order M", "order"},
    {"exponential_end", "exponential-end"},
    {"cvode.rtol", "rtol"},
    {"cvode.atol", "atol"},
    {"cvode.max_order", "max-order"},
    {"noise_model", "noise-model"},
    {"force_noise_sd", "force-noise-sd"},
    {"noise_sd", "noise-sd"},
};

bool word_start(const std::string& text, std::size_t at) {
  return at == 0 || !(std::isalnum(static_cast<unsigned char>(text[at - 1])) || text[at - 1] == '_' ||
                      text[at - 1] == '.' || text[at - 1] == '-');
}

}  // namespace

std::string in_flags(std::string message) {
  for (const auto& [field, flag] : kFlagOfField) {
    const std::string key = std::string(field) + " = ";
    for (std::size_t at = message.find(key); at != std::string::npos; at = message.find(key, at + 1)) {
      if (!word_start(message, at)) continue;
      // The value runs to the next ':' or ',' or ' ' (a number or a word).
      const std::size_t begin = at + key.size();
      const std::size_t end = std::min(message.find_first_of(":, )", begin), message.size());
      std::string value = message.substr(begin, end - begin);
      if (value.size() >= 2 && value.front() == '\'' && value.back() == '\'') value = value.substr(1, value.size() - 2);
      const std::string replacement = "--" + std::string(flag) + " = '" + value + "'";
      message.replace(at, end - at, replacement);
      at += replacement.size() - 1;
    }
  }
  return message;
}

void refuse(const Caller& caller, const std::string& field, const std::string& value, const std::string& constraint) {
  throw InputError(caller.label + ": --" + field + " = '" + value + "': " + in_flags(constraint));
}

void refuse(const Caller& caller, const std::string& message) {
  throw InputError(caller.label + ": " + in_flags(message));
}

}  // namespace beamid::api
