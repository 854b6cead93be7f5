#pragma once
// Gauss–Legendre nodes and weights on [−1, 1] (Abramowitz & Stegun, Table 25.4): the n-point rule
// is exact for polynomials of degree ≤ 2n − 1. One home for every quadrature of the code base:
// the 2- and 3-point rules of the specular march and the column tables, the 4-point rule of the
// sky integrals over visible sets, the 8-point rule of the atmosphere's optical depths and
// irradiance checks (given by its positive half: nodes ±x_k share the weight w_k).
namespace skyband {

inline constexpr double kGauss2Nodes[2] = {-0.5773502691896258, 0.5773502691896258};  // ±1/√3
inline constexpr double kGauss2Weights[2] = {1.0, 1.0};

inline constexpr double kGauss3Nodes[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};  // 0, ±√(3/5)
inline constexpr double kGauss3Weights[3] = {0.5555555555555556, 0.8888888888888888, 0.5555555555555556};

inline constexpr double kGauss4Nodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
inline constexpr double kGauss4Weights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};

inline constexpr double kGauss8HalfNodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
inline constexpr double kGauss8HalfWeights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

}  // namespace skyband
