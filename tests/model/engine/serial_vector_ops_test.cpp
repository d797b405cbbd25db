// The compiled vector kernels (model/engine/serial_vector_ops.h) against the library's own serial kernels, on a length
// that is not a multiple of the four partial sums, and the fused operations with the aliasing CVODE uses.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include "model/engine/serial_vector_ops.h"

namespace turbodyn {
namespace {

class VectorOps : public ::testing::Test {
 protected:
  static constexpr int kN = 37;
  void SetUp() override {
    SUNContext_Create(nullptr, &ctx_);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (int k = 0; k < 6; ++k) {
      lib_.push_back(N_VNew_Serial(kN, ctx_));
      ours_.push_back(N_VNew_Serial(kN, ctx_));
      UseCompiledVectorOps(ours_.back());
      for (int i = 0; i < kN; ++i) {
        const double x = k == 5 ? (i % 3 == 0 ? 1.0 : -1.0) : u(rng);  // vector 5: a mask with both signs
        NV_Ith_S(lib_[k], i) = NV_Ith_S(ours_[k], i) = x;
      }
    }
  }
  void TearDown() override {
    for (N_Vector v : lib_) N_VDestroy(v);
    for (N_Vector v : ours_) N_VDestroy(v);
    SUNContext_Free(&ctx_);
  }
  // Largest difference between the library's and our vector k, relative to the largest entry.
  double Difference(int k) const {
    double d = 0.0, m = 0.0;
    for (int i = 0; i < kN; ++i) {
      d = std::max(d, std::abs(NV_Ith_S(lib_[k], i) - NV_Ith_S(ours_[k], i)));
      m = std::max(m, std::abs(NV_Ith_S(lib_[k], i)));
    }
    return d / std::max(m, 1e-300);
  }
  SUNContext ctx_ = nullptr;
  std::vector<N_Vector> lib_, ours_;
};

TEST_F(VectorOps, ElementwiseOperationsEqualTheLibrarys) {
  const auto both = [&](auto op) {
    op(lib_);
    op(ours_);
  };
  both([](auto& v) { N_VLinearSum(0.3, v[0], -1.7, v[1], v[2]); });
  EXPECT_EQ(Difference(2), 0.0);
  both([](auto& v) { N_VLinearSum(1.0, v[2], 0.25, v[0], v[2]); });  // z aliases x
  EXPECT_EQ(Difference(2), 0.0);
  both([](auto& v) { N_VProd(v[0], v[1], v[3]); });
  EXPECT_EQ(Difference(3), 0.0);
  both([](auto& v) { N_VDiv(v[0], v[1], v[3]); });
  EXPECT_EQ(Difference(3), 0.0);
  both([](auto& v) { N_VScale(-3.5, v[0], v[3]); });
  EXPECT_EQ(Difference(3), 0.0);
  both([](auto& v) { N_VAbs(v[1], v[3]); });
  EXPECT_EQ(Difference(3), 0.0);
  both([](auto& v) { N_VInv(v[1], v[3]); });
  EXPECT_EQ(Difference(3), 0.0);
  both([](auto& v) { N_VAddConst(v[1], 0.125, v[3]); });
  EXPECT_EQ(Difference(3), 0.0);
  both([](auto& v) { N_VCompare(1.0, v[1], v[3]); });
  EXPECT_EQ(Difference(3), 0.0);
  both([](auto& v) { N_VConst(2.5, v[3]); });
  EXPECT_EQ(Difference(3), 0.0);
  EXPECT_EQ(N_VInvTest(lib_[0], lib_[4]), N_VInvTest(ours_[0], ours_[4]));
  EXPECT_EQ(Difference(4), 0.0);
  NV_Ith_S(lib_[1], 5) = NV_Ith_S(ours_[1], 5) = 0.0;
  EXPECT_EQ(N_VInvTest(lib_[1], lib_[4]), SUNFALSE);
  EXPECT_EQ(N_VInvTest(ours_[1], ours_[4]), SUNFALSE);
}

TEST_F(VectorOps, ReductionsEqualTheLibrarysToRoundOff) {
  // Only the order of summation differs: a few units in the last place.
  const double tol = 1e-14;
  const auto close = [&](double a, double b) { EXPECT_NEAR(a, b, tol * std::abs(a)) << a << " " << b; };
  close(N_VDotProd(lib_[0], lib_[1]), N_VDotProd(ours_[0], ours_[1]));
  close(N_VWrmsNorm(lib_[0], lib_[1]), N_VWrmsNorm(ours_[0], ours_[1]));
  close(N_VWrmsNormMask(lib_[0], lib_[1], lib_[5]), N_VWrmsNormMask(ours_[0], ours_[1], ours_[5]));
  close(N_VWL2Norm(lib_[0], lib_[1]), N_VWL2Norm(ours_[0], ours_[1]));
  close(N_VL1Norm(lib_[0]), N_VL1Norm(ours_[0]));
  close(N_VWSqrSumLocal(lib_[0], lib_[1]), N_VWSqrSumLocal(ours_[0], ours_[1]));
  close(N_VWSqrSumMaskLocal(lib_[0], lib_[1], lib_[5]), N_VWSqrSumMaskLocal(ours_[0], ours_[1], ours_[5]));
  EXPECT_EQ(N_VMaxNorm(lib_[0]), N_VMaxNorm(ours_[0]));
  EXPECT_EQ(N_VMin(lib_[0]), N_VMin(ours_[0]));
  // The mask really selects: the masked norm is below the full one.
  EXPECT_LT(N_VWrmsNormMask(ours_[0], ours_[1], ours_[5]), N_VWrmsNorm(ours_[0], ours_[1]));
}

TEST_F(VectorOps, FusedOperationsEqualTheGenericSequenceAlsoWhenTheOutputIsAnInput) {
  double c[5] = {1.0, -0.5, 2.0, 0.75, -1.25};
  // The library's vectors have no fused kernels: N_VLinearCombination falls back to a scale and linear sums.
  ASSERT_EQ(lib_[0]->ops->nvlinearcombination, nullptr);
  N_VLinearCombination(5, c, lib_.data(), lib_[5]);
  N_VLinearCombination(5, c, ours_.data(), ours_[5]);
  EXPECT_EQ(Difference(5), 0.0);
  N_VLinearCombination(4, c, lib_.data(), lib_[0]);  // z == X[0], as in CVODE's predictor
  N_VLinearCombination(4, c, ours_.data(), ours_[0]);
  EXPECT_EQ(Difference(0), 0.0);
  // Ours also allows z == X[k] for k > 0 (the library's generic sequence does not: it overwrites X[k] first).
  std::vector<double> expect(kN);
  for (int i = 0; i < kN; ++i)
    expect[i] = c[1] * NV_Ith_S(ours_[1], i) + c[2] * NV_Ith_S(ours_[2], i) + c[3] * NV_Ith_S(ours_[3], i);
  N_VLinearCombination(3, c + 1, ours_.data() + 1, ours_[2]);
  for (int i = 0; i < kN; ++i) EXPECT_EQ(NV_Ith_S(ours_[2], i), expect[i]) << i;
  for (int i = 0; i < kN; ++i) NV_Ith_S(lib_[2], i) = expect[i];

  double a[3] = {0.5, -2.0, 3.0};
  N_Vector ly[3] = {lib_[1], lib_[2], lib_[3]}, oy[3] = {ours_[1], ours_[2], ours_[3]};
  N_VScaleAddMulti(3, a, lib_[0], ly, ly);  // Z == Y
  N_VScaleAddMulti(3, a, ours_[0], oy, oy);
  for (int k = 1; k <= 3; ++k) EXPECT_EQ(Difference(k), 0.0) << k;
  N_Vector lz[3] = {lib_[4], lib_[5], lib_[2]}, oz[3] = {ours_[4], ours_[5], ours_[2]};
  N_VScaleAddMulti(3, a, lib_[0], ly, lz);
  N_VScaleAddMulti(3, a, ours_[0], oy, oz);
  for (int k = 2; k <= 5; ++k) EXPECT_EQ(Difference(k), 0.0) << k;
}

TEST_F(VectorOps, ClonesInheritTheKernels) {
  N_Vector c = N_VClone(ours_[0]);
  EXPECT_EQ(c->ops->nvwrmsnorm, ours_[0]->ops->nvwrmsnorm);
  EXPECT_NE(c->ops->nvwrmsnorm, lib_[0]->ops->nvwrmsnorm);
  EXPECT_NE(c->ops->nvlinearcombination, nullptr);
  N_VDestroy(c);
}

}  // namespace
}  // namespace turbodyn
