#include "line_quadrature.h"

#include <cmath>

namespace fibrecheck {

LineQuadrature LineQuadrature::slices(int n) {
  LineQuadrature q;
  for (int i = 0; i < n; ++i) {
    q.position.push_back((i + 0.5) / n);
    q.weight.push_back(1.0 / n);
  }
  return q;
}

LineQuadrature LineQuadrature::gauss(int cells) {
  LineQuadrature q;
  const double offset = 0.5 / std::sqrt(3.0);  // Gauss points ±1/√3 on a cell of length 1
  for (int i = 0; i < cells; ++i)
    for (double g : {-offset, offset}) {
      q.position.push_back((i + 0.5 + g) / cells);
      q.weight.push_back(0.5 / cells);
    }
  return q;
}

}  // namespace fibrecheck
