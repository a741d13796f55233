#include "eqhb/size_limits.h"

#include <cstdio>

#include "eqhb/error.h"

namespace eqhb {

void checkBytes(const std::string& field, const std::string& value, const std::string& what, double bytes) {
  if (bytes <= kMaxModelBytes) return;
  char size[64];
  std::snprintf(size, sizeof size, "%.3g GiB", bytes / (1024.0 * 1024 * 1024));
  throwInputError(field, value,
                  what + " needs about " + size + ", more than the " +
                      formatNumber(kMaxModelBytes / (1024.0 * 1024 * 1024)) + " GiB limit");
}

}  // namespace eqhb
