#pragma once
// The three-node rule of a refined band (docs/geometry.md, band refinement): the weights with
// which a band's two edge lines and its δ-midpoint line combine into ∫ g(δ) cos(δ − β) dδ.
namespace skyband {

// Weights (w0, wm, w1) of the interpolatory rule on nodes δ0, δm, δ1 for ∫_{δ0}^{δ1} g(δ) cos(δ − β) dδ
// (exact for quadratic g), and m0 = ∫ cos(δ − β) dδ, the midpoint rule's weight. With t = δ − δm,
// h = (δ1 − δ0)/2, γ = δm − β, the moments of cos(t + γ) over [−h, h] are
//   m0 = 2 sin h cos γ,  m1 = −2 sin γ (sin h − h cos h),  m2 = 2 cos γ ((h² − 2) sin h + 2h cos h),
// and the Lagrange weights are w0 = (m2 − h m1)/2h², wm = (h² m0 − m2)/h², w1 = (m2 + h m1)/2h².
// Integrating in δ, not in s = sin(δ − β), matters: f is smooth in δ but has a square-root
// singularity in s at the face's own plane (δ − β = ±π/2).
struct BandRule {
  double w0, wm, w1, m0;
};
BandRule band_rule(double d0, double d1, double beta);

}  // namespace skyband
