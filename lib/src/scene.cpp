// Scene files (placeholder until the reader lands).
#include "soa/scene.hpp"

namespace soa {

Scene load_scene(const std::string& path) { throw Error(path + ": scene reader not built yet"); }
Scene parse_scene(const std::string&, const std::string& name) {
  throw Error(name + ": scene reader not built yet");
}

}  // namespace soa
