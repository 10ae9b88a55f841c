#include "api/request.h"

#include "core/errors.h"

namespace beamid::api {

void refuse(const Caller& caller, const std::string& field, const std::string& value, const std::string& constraint) {
  throw InputError(caller.label + ": --" + field + " = '" + value + "': " + constraint);
}

void refuse(const Caller& caller, const std::string& message) { throw InputError(caller.label + ": " + message); }

}  // namespace beamid::api
