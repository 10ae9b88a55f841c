// What every typed request shares: the label its errors start with, and the one-line form of a violated field.
//
// A request (api/*_request.h) is a plain struct holding what a user chose for one computation, with the command
// line's defaults; an unset optional takes the default of the options struct below it. The command line fills a
// request from its flags (apps/), the Python package from its keyword arguments, a C++ program directly; the
// request's compute function validates it and computes, and nothing below it reads a flag.
//
// A field is named as the command line spells it ("bound-factor"; Python's keyword is the same with underscores), so
// that an error reads alike from every front end:
//   beamid fit: --bound-factor = '0.5': must be > 1
#pragma once

#include <string>

namespace beamid::api {

// What a request's errors start with ("beamid fit" by default, as on the command line).
struct Caller {
  std::string label;
};

// InputError "label: --field = 'value': constraint". The value is the field's text: a number's shortest round-trip
// form (format_value), an integer's decimal digits.
[[noreturn]] void refuse(const Caller& caller, const std::string& field, const std::string& value,
                         const std::string& constraint);
// A lower layer's message with the option fields it names written as the flags that set them ("sensor_x_m = 0.5"
// becomes "--sensor-x = '0.5'"); refuse applies it.
std::string in_flags(std::string message);
// InputError "label: message": a constraint between fields, or a lower layer's message with its own key.
[[noreturn]] void refuse(const Caller& caller, const std::string& message);

}  // namespace beamid::api
