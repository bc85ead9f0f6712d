#include "laytracks/brep/part.hpp"

namespace laytracks {

std::string Part::patch_label(PatchId p) const {
  return "patch \"" + patches[p.index()].name + "\" (index " + std::to_string(p.index()) + ")";
}

}  // namespace laytracks
