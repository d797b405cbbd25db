// BlockArrowLU against a dense LU of the same matrix.
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "model/engine/block_arrow_lu.h"

namespace turbodyn {
namespace {

// A random, well-conditioned block-arrow matrix: diagonal blocks, border rows and columns, zeros elsewhere.
Eigen::MatrixXd block_arrow(const std::vector<int>& blocks, int border, unsigned seed) {
  int n = border;
  for (int s : blocks) n += s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  int o = 0;
  for (int s : blocks) {
    for (int i = 0; i < s; ++i)
      for (int j = 0; j < s; ++j) A(o + i, o + j) = u(rng);
    o += s;
  }
  for (int i = 0; i < n; ++i)
    for (int j = o; j < n; ++j) A(i, j) = u(rng), A(j, i) = u(rng);
  A.diagonal().array() += 4.0;
  return A;
}

// lu, factored from A, solves four right-hand sides at once and one alone as a dense LU of A does.
void expect_solves_like_dense_lu(BlockArrowLU& lu, const Eigen::MatrixXd& A, const std::string& label) {
  constexpr double kTolerance = 1e-12;
  const int n = static_cast<int>(A.rows());
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(n, 4);
  Eigen::MatrixXd x = b;
  lu.solve_in_place(x);
  const Eigen::MatrixXd reference = A.partialPivLu().solve(b);
  EXPECT_LT((x - reference).cwiseAbs().maxCoeff(), kTolerance * reference.cwiseAbs().maxCoeff()) << label;
  Eigen::VectorXd v = b.col(0);  // one column, as the Newton solve gives it
  lu.solve_in_place(v);
  EXPECT_LT((v - reference.col(0)).cwiseAbs().maxCoeff(), kTolerance * reference.cwiseAbs().maxCoeff()) << label;
}

TEST(BlockArrowLU, SolvesLikeADenseLUForBlocksWithAndWithoutBorder) {
  const std::vector<std::pair<std::vector<int>, int>> cases = {
      {{9, 9, 9, 9, 9, 9, 9, 9}, 10}, {{9, 9, 9, 9, 9, 9, 9, 9}, 14}, {{9, 9, 9}, 0}, {{}, 7}, {{3, 5}, 1}};
  unsigned seed = 1;
  for (const auto& [blocks, border] : cases) {
    const Eigen::MatrixXd A = block_arrow(blocks, border, seed++);
    const int n = static_cast<int>(A.rows());
    BlockArrowLU lu(n, blocks, 4);
    ASSERT_TRUE(lu.compute(A));
    expect_solves_like_dense_lu(lu, A, std::to_string(blocks.size()) + " blocks, border " + std::to_string(border));
  }
}

TEST(BlockArrowLU, ReportsASingularBlock) {
  Eigen::MatrixXd A = block_arrow({4, 4}, 3, 7);
  A.block(4, 4, 4, 4).setZero();  // the second diagonal block
  BlockArrowLU lu(11, {4, 4}, 1);
  EXPECT_FALSE(lu.compute(A));
}

// The Newton block I - g J is factored from J itself: a block of a larger matrix (its outer stride), scaled and
// shifted, for the compiled ball sizes (blocks of 9, borders 10 and 14) and any other.
TEST(BlockArrowLU, FactorsAShiftedScaledBlockOfALargerMatrix) {
  const std::vector<std::pair<std::vector<int>, int>> cases = {
      {{9, 9, 9, 9, 9, 9, 9, 9}, 10}, {{9, 9, 9, 9, 9, 9, 9, 9}, 14}, {{4, 6}, 3}};
  unsigned seed = 11;
  for (const auto& [blocks, border] : cases) {
    const Eigen::MatrixXd G = block_arrow(blocks, border, seed++);
    const int n = static_cast<int>(G.rows());
    Eigen::MatrixXd J = Eigen::MatrixXd::Random(n + 5, n + 7);  // G sits at (3, 5) of J
    J.block(3, 5, n, n) = G;
    const double scale = -0.37, shift = 1.0;
    BlockArrowLU lu(n, blocks, 4);
    ASSERT_TRUE(lu.compute(J.block(3, 5, n, n), scale, shift));
    const Eigen::MatrixXd A = shift * Eigen::MatrixXd::Identity(n, n) + scale * G;
    expect_solves_like_dense_lu(lu, A, std::to_string(blocks.size()) + " blocks, border " + std::to_string(border));
  }
}

TEST(BlockArrowLU, ReportsASingularBallBlockAndASingularSchurComplement) {
  const std::vector<int> balls(8, 9);
  Eigen::MatrixXd A = block_arrow(balls, 10, 5);
  A.block(27, 27, 9, 9).setZero();  // the fourth ball
  BlockArrowLU lu(82, balls, 1);
  EXPECT_FALSE(lu.compute(A));
  // Regular blocks, but a border row of zeros: A and its Schur complement are singular.
  A = block_arrow(balls, 10, 6);
  A.row(81).setZero();
  EXPECT_FALSE(lu.compute(A));
}

// Kinematic blocks: each block's first k rows of G are [0 I 0] (the positions' rates are the next k states) and zero
// in the border columns. The factorisation through the velocity rows solves as a dense LU of shift I + scale G, and
// does not read those rows (they are overwritten with noise here); for the compiled ball sizes and run-time ones.
TEST(BlockArrowLU, FactorsKinematicBlocksThroughTheirVelocityRows) {
  struct Case {
    std::vector<int> blocks;
    int border, k;
  };
  const std::vector<Case> cases = {{{9, 9, 9, 9, 9, 9, 9, 9}, 10, 3},
                                   {{9, 9, 9, 9, 9, 9, 9, 9}, 14, 3},
                                   {{9, 9, 9}, 0, 3},
                                   {{4, 6, 5}, 3, 2},
                                   {{2, 3}, 2, 1}};
  unsigned seed = 21;
  for (const Case& cs : cases) {
    Eigen::MatrixXd G = block_arrow(cs.blocks, cs.border, seed++);
    const int n = static_cast<int>(G.rows());
    int o = 0;
    for (int s : cs.blocks) {
      for (int r = 0; r < cs.k; ++r) {
        G.row(o + r).setZero();
        G(o + r, o + cs.k + r) = 1.0;
      }
      o += s;
    }
    for (const double shift : {1.0, 0.8}) {
      const double scale = -0.37;
      const Eigen::MatrixXd A = shift * Eigen::MatrixXd::Identity(n, n) + scale * G;
      Eigen::MatrixXd noisy = G;
      o = 0;
      for (int s : cs.blocks) {
        noisy.block(o, 0, cs.k, n).setRandom();
        o += s;
      }
      BlockArrowLU lu(n, cs.blocks, 4, cs.k);
      ASSERT_TRUE(lu.compute(noisy, scale, shift));
      const std::string label = std::to_string(cs.blocks.size()) + " blocks, border " + std::to_string(cs.border) +
                                ", k " + std::to_string(cs.k) + ", shift " + std::to_string(shift);
      expect_solves_like_dense_lu(lu, A, label);
      // Without a shift the kinematic path does not apply: A itself is factored, every row read.
      ASSERT_TRUE(lu.compute(A));
      expect_solves_like_dense_lu(lu, A, label + ", plain");
    }
  }
  EXPECT_THROW(BlockArrowLU(10, {4, 4}, 1, 3), std::invalid_argument);
}

TEST(BlockArrowLU, RefusesBlocksLargerThanTheMatrix) { EXPECT_THROW(BlockArrowLU(5, {3, 3}, 1), std::invalid_argument); }

}  // namespace
}  // namespace turbodyn
