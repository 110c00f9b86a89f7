// Messages as JSON, field names as in the .proto: `photonfarm ... --json` and the dashboard's
// JSON endpoints print the same text for the same message.
#pragma once

#include <google/protobuf/message.h>

#include <string>

namespace pf {

// One line of JSON; every field present, defaults included.
std::string ToJson(const google::protobuf::Message& message);

}  // namespace pf
