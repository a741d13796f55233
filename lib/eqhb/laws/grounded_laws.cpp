#include "eqhb/laws/grounded_laws.h"

#include "eqhb/error.h"

namespace eqhb {

void requireGroundedLaws(const std::vector<AttachedLaw>& laws, const std::string& computation) {
  for (size_t l = 0; l < laws.size(); ++l)
    if (!laws[l].attachment.grounded())
      throwInputError("law[" + std::to_string(l) + "].between", laws[l].attachment.describe(),
                      "a " + laws[l].law->type() + " law between two nodes: " + computation +
                          " handle laws on one DOF per component against the ground only");
}

}  // namespace eqhb
