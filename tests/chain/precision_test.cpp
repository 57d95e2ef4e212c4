/// \file
/// The core identity of lessons 3-4, recursions = operator forms, in float, double and long
/// double (typed tests): on random chains with every hinge type, gravity and external
/// forces, the velocity, acceleration and Newton-Euler recursions against
///   V = phi* H* beta,  alpha = phi* (H* beta_dot + a),  f = phi (M alpha + b),  T = H f,
/// with residuals relative to the product of the norms of the factors, in units of
/// N eps<S> (N = 6n): the same bound in every precision.
#include "chain_support.hpp"

namespace soa::test {
namespace {

template <class S>
class chain_Precision : public ::testing::Test {};
TYPED_TEST_SUITE(chain_Precision, Precisions, ScalarNames);

constexpr int kMaxBodies = 8;
constexpr double kTol = 2.0;  // as in operators_test.cpp (worst seen: 0.05)

TYPED_TEST(chain_Precision, RecursionsMatchOperatorForms) {
  using S = TypeParam;
  const std::string p = " (" + scalar_name<S>() + ") [N eps]";
  Random<S> rnd;
  Worst wV("V = phi* H* beta" + p), wa("alpha = phi* (H* beta_dot + a)" + p),
      wf("f = phi (M alpha + b)" + p), wT("T = H f" + p);
  for (int i = 0; i < kCases; ++i) {
    ChainOptions opt;
    opt.gravity = true;
    const ModelT<S> m = random_chain(rnd, chain_size(i, kMaxBodies), opt);
    const int n = m.n();
    const double units = 6 * n * double(eps<S>());
    const StateT<S> x = random_state(rnd, m);
    const VecX<S> beta_dot = random_vector(rnd, m.nv());
    const ExternalForces<S> f_ext = random_forces(rnd, m);
    const OperatorsT<S> op = OperatorsT<S>::build(m, x, f_ext);
    const double nphi = double(op.phi.norm()), nH = double(op.H.norm());
    const double nM = double(op.M.norm());

    WorkspaceT<S> ws(m);
    VecX<S> T(m.nv());
    inverse_dynamics(m, x, beta_dot, f_ext, ws, T);  // fills V, alpha, f as well
    const double s_V = nphi * nH * double(x.beta.norm());
    const double s_alpha = nphi * (nH * double(beta_dot.norm()) + double(op.a.norm()));
    const double s_f = nphi * (nM * s_alpha + double(op.b.norm()));
    wV.add(residual(stack(ws.V), op.V(x.beta), s_V) / units, i);
    wa.add(residual(stack(ws.alpha), op.alpha(beta_dot), s_alpha) / units, i);
    wf.add(residual(stack(ws.f), op.f(beta_dot), s_f) / units, i);
    wT.add(residual(T, op.T(beta_dot), nH * s_f) / units, i);
  }
  EXPECT_LE(wV.value(), kTol);
  EXPECT_LE(wa.value(), kTol);
  EXPECT_LE(wf.value(), kTol);
  EXPECT_LE(wT.value(), kTol);
}

}  // namespace
}  // namespace soa::test
