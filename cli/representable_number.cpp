#include "representable_number.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace eqhb::cli {

const CLI::Validator& representableNumber() {
  static const CLI::Validator check(
      [](std::string& text) -> std::string {
        errno = 0;
        char* end = nullptr;
        const double parsed = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || errno != ERANGE) return "";
        // ERANGE also flags subnormal results, which keep a (reduced) precision.
        if (parsed == 0.0)
          return text + " underflows to 0; not representable (the smallest positive double is about 4.9e-324)";
        if (std::isinf(parsed)) return text + " overflows; not representable (the largest double is about 1.8e308)";
        return "";
      },
      "", "representable number");
  return check;
}

}  // namespace eqhb::cli
