#include "model/io/result_header.h"

namespace turbodyn {

const char* turbodyn_version() { return TURBODYN_VERSION; }

nlohmann::json result_header(const MachineSpec& spec, const std::vector<Override>& overrides) {
  nlohmann::json j;
  j["turbodyn_version"] = turbodyn_version();
  j["model"] = {{"name", spec.name}, {"source", spec.source.string()}};
  nlohmann::json list = nlohmann::json::array();
  for (const Override& o : overrides) list.push_back(o.path + "=" + o.value);
  j["overrides"] = list;
  return j;
}

}  // namespace turbodyn
