#include "lighting/brdf/fresnel_factors.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/SVD>

namespace skyband {

FresnelFactors::FresnelFactors(const FresnelTable& table, double max_abs_error)
    : u_(static_cast<std::size_t>(FresnelTable::kNodes) * kMaxRank, 0.0) {
  if (!(max_abs_error > 0.0)) throw std::invalid_argument("FresnelFactors: tolerance must be > 0");
  constexpr int kRows = FresnelTable::kNodes;
  Eigen::MatrixXd a(kRows, kSpectrumSamples);
  for (int j = 0; j < kRows; ++j)
    for (int i = 0; i < kSpectrumSamples; ++i) a(j, i) = table.node_value(j, i);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::MatrixXd& U = svd.matrixU();
  const Eigen::MatrixXd& V = svd.matrixV();
  const Eigen::VectorXd& sigma = svd.singularValues();
  Eigen::MatrixXd approx = Eigen::MatrixXd::Zero(kRows, kSpectrumSamples);
  for (int r = 1; r <= kMaxRank; ++r) {
    approx += sigma(r - 1) * U.col(r - 1) * V.col(r - 1).transpose();
    const double err = (a - approx).cwiseAbs().maxCoeff();
    if (err <= max_abs_error) {
      rank_ = r;
      max_error_ = err;
      for (int k = 0; k < r; ++k) {
        for (int i = 0; i < kSpectrumSamples; ++i) v_[static_cast<std::size_t>(k)][i] = V(i, k);
        for (int j = 0; j < kRows; ++j)
          u_[static_cast<std::size_t>(j) * kMaxRank + static_cast<std::size_t>(k)] = sigma(k) * U(j, k);
      }
      return;
    }
  }
  throw std::invalid_argument("FresnelFactors: no rank <= " + std::to_string(kMaxRank) +
                              " approximates the Fresnel table within " + std::to_string(max_abs_error));
}

}  // namespace skyband
