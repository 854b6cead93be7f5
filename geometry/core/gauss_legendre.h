#pragma once
// Gauss–Legendre nodes and weights on [−1, 1] (Abramowitz & Stegun, Table 25.4): the 4-point rule,
// exact for polynomials of degree ≤ 7, used by every quadrature of the sky over visible sets.
namespace skyband {

inline constexpr double kGauss4Nodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
inline constexpr double kGauss4Weights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};

}  // namespace skyband
