// Compliant normal contact against the exact Signorini law (spec §5): the
// contact-friction scene solved with the elastic layer p = k_n max(0, −g)
// for k_n = 1 .. 1e6 and with the min form, each from rest with the own
// dogleg on the condensed and the full system. The distance to the exact
// answer should fall like 1/k_n (the layer's penetration is p/k_n).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace eqhb::bench {

struct CompliantRow {
  std::string scene, system;
  double k_n = 0.0;            // 0: the exact (min form) solve
  bool converged = false;
  std::string termination;
  int iterations = 0, residual_evaluations = 0;
  double seconds = 0.0;
  double distance = 0.0;       // ‖x − x_exact‖ / ‖x_exact‖ over the displacement coefficients (NaN if either failed)
  double penetration = 0.0;    // max(−g) / max|g| sampled densely
};

// The scene's first law must be contact-friction; its other settings stay.
std::vector<CompliantRow> compliantStudy(const std::filesystem::path& scene, const std::vector<double>& stiffnesses);

std::string compliantReport(const std::vector<CompliantRow>& rows);
std::string compliantIntroduction();

}  // namespace eqhb::bench
