// JSON printing through protobuf's own mapping.
#include "wire/json.h"

#include <google/protobuf/util/json_util.h>

namespace pf {

std::string ToJson(const google::protobuf::Message& message) {
    google::protobuf::util::JsonPrintOptions options;
    options.preserve_proto_field_names = true;
    options.always_print_primitive_fields = true;
    std::string json;
    (void)google::protobuf::util::MessageToJsonString(message, &json, options);
    return json;
}

}  // namespace pf
