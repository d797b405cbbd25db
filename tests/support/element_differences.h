// Plain forward differences of a force element, the reference its own Jacobian (add_jacobian) is tested against.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "model/elements/force_element.h"

namespace turbodyn::testing {

/// The element's forces on its 4 shaft DOFs, then the rates of its m states, at (q, v, z).
inline std::vector<double> element_outputs(const ForceElement& e, const SpinState& s, const double* q,
                                           const double* v, const double* z, int m, ElementWorkspace& ws) {
  std::vector<double> out(4 + m, 0.0);
  e.calc_and_add_forces(s, q, v, z, ws, out.data(), out.data() + 4);
  return out;
}

/// Forward differences of element_outputs in q, v and z (columns in that order) with the element's own steps
/// (fd_step), column-major: entry (r, j) at j * (4 + m) + r.
inline std::vector<double> forward_differences(const ForceElement& e, const SpinState& s, const double* q,
                                               const double* v, const double* z, int m, ElementWorkspace& ws) {
  constexpr int d = 4;
  const int rows = d + m, cols = 2 * d + m;
  std::vector<double> in(cols), fd(static_cast<std::size_t>(rows * cols));
  std::copy(q, q + d, in.begin());
  std::copy(v, v + d, in.begin() + d);
  std::copy(z, z + m, in.begin() + 2 * d);
  const auto at = [&] { return element_outputs(e, s, in.data(), in.data() + d, in.data() + 2 * d, m, ws); };
  const std::vector<double> out0 = at();
  for (int j = 0; j < cols; ++j) {
    const double saved = in[j], h = e.fd_step(j, d, saved);
    in[j] = saved + h;
    const std::vector<double> out1 = at();
    in[j] = saved;
    for (int r = 0; r < rows; ++r) fd[j * rows + r] = (out1[r] - out0[r]) / h;
  }
  return fd;
}

/// The element's own Jacobian `own` against `reference` (forward differences, or another own Jacobian), both
/// column-major (4 + m) x (8 + m): each column scaled by its typical value (fd_step / fd_relative_step), each entry
/// within `tolerance` of the largest scaled entry of its row in `reference`. Columns with skip(j) are not compared.
template <class Skip>
void expect_jacobian_near(const ForceElement& e, const std::vector<double>& own, const std::vector<double>& reference,
                          int m, double tolerance, Skip skip, const std::string& what) {
  constexpr int d = 4;
  const int rows = d + m, cols = 2 * d + m;
  auto typical = [&](int j) { return e.fd_step(j, d, 0.0) / e.fd_relative_step(); };
  for (int r = 0; r < rows; ++r) {
    double row_scale = 0.0;
    for (int j = 0; j < cols; ++j) row_scale = std::max(row_scale, std::abs(reference[j * rows + r]) * typical(j));
    if (row_scale == 0.0) continue;
    for (int j = 0; j < cols; ++j) {
      if (skip(j)) continue;
      EXPECT_NEAR(own[j * rows + r] * typical(j), reference[j * rows + r] * typical(j), tolerance * row_scale)
          << "row " << r << ", column " << j << what;
    }
  }
}

}  // namespace turbodyn::testing
