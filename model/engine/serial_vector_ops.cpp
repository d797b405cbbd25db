#include "model/engine/serial_vector_ops.h"

#include <algorithm>
#include <cmath>

namespace turbodyn {
namespace {

using Index = sunindextype;

inline double* data(N_Vector v) { return NV_DATA_S(v); }
inline Index size(N_Vector v) { return NV_LENGTH_S(v); }

// Reductions with four partial sums in a fixed order: vectorisable without reassociation by the compiler, and
// the same result for the same data on every run.
template <class Term>
double Sum(Index n, Term term) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  Index i = 0;
  for (; i + 4 <= n; i += 4) {
    s0 += term(i);
    s1 += term(i + 1);
    s2 += term(i + 2);
    s3 += term(i + 3);
  }
  for (; i < n; ++i) s0 += term(i);
  return (s0 + s1) + (s2 + s3);
}

void LinearSum(double a, N_Vector x, double b, N_Vector y, N_Vector z) {
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  const Index n = size(z);
  for (Index i = 0; i < n; ++i) zd[i] = a * xd[i] + b * yd[i];
}

void Const(double c, N_Vector z) {
  double* zd = data(z);
  std::fill(zd, zd + size(z), c);
}

void Prod(N_Vector x, N_Vector y, N_Vector z) {
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  const Index n = size(z);
  for (Index i = 0; i < n; ++i) zd[i] = xd[i] * yd[i];
}

void Div(N_Vector x, N_Vector y, N_Vector z) {
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  const Index n = size(z);
  for (Index i = 0; i < n; ++i) zd[i] = xd[i] / yd[i];
}

void Scale(double c, N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  const Index n = size(z);
  for (Index i = 0; i < n; ++i) zd[i] = c * xd[i];
}

void Abs(N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  const Index n = size(z);
  for (Index i = 0; i < n; ++i) zd[i] = std::abs(xd[i]);
}

void Inv(N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  const Index n = size(z);
  for (Index i = 0; i < n; ++i) zd[i] = 1.0 / xd[i];
}

void AddConst(N_Vector x, double b, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  const Index n = size(z);
  for (Index i = 0; i < n; ++i) zd[i] = xd[i] + b;
}

double DotProd(N_Vector x, N_Vector y) {
  const double *xd = data(x), *yd = data(y);
  return Sum(size(x), [=](Index i) { return xd[i] * yd[i]; });
}

double MaxNorm(N_Vector x) {
  const double* xd = data(x);
  double m = 0.0;
  for (Index i = 0, n = size(x); i < n; ++i) m = std::max(m, std::abs(xd[i]));
  return m;
}

double WSqrSum(N_Vector x, N_Vector w) {
  const double *xd = data(x), *wd = data(w);
  return Sum(size(x), [=](Index i) {
    const double p = xd[i] * wd[i];
    return p * p;
  });
}

double WSqrSumMask(N_Vector x, N_Vector w, N_Vector id) {
  const double *xd = data(x), *wd = data(w), *idd = data(id);
  return Sum(size(x), [=](Index i) {
    const double p = idd[i] > 0.0 ? xd[i] * wd[i] : 0.0;
    return p * p;
  });
}

double WrmsNorm(N_Vector x, N_Vector w) { return std::sqrt(WSqrSum(x, w) / static_cast<double>(size(x))); }

double WrmsNormMask(N_Vector x, N_Vector w, N_Vector id) {
  return std::sqrt(WSqrSumMask(x, w, id) / static_cast<double>(size(x)));
}

double Min(N_Vector x) {
  const double* xd = data(x);
  double m = xd[0];
  for (Index i = 1, n = size(x); i < n; ++i) m = std::min(m, xd[i]);
  return m;
}

double WL2Norm(N_Vector x, N_Vector w) { return std::sqrt(WSqrSum(x, w)); }

double L1Norm(N_Vector x) {
  const double* xd = data(x);
  return Sum(size(x), [=](Index i) { return std::abs(xd[i]); });
}

void Compare(double c, N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  const Index n = size(z);
  for (Index i = 0; i < n; ++i) zd[i] = std::abs(xd[i]) >= c ? 1.0 : 0.0;
}

booleantype InvTest(N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  bool no_zero = true;
  for (Index i = 0, n = size(z); i < n; ++i) {
    if (xd[i] == 0.0) {
      no_zero = false;
    } else {
      zd[i] = 1.0 / xd[i];
    }
  }
  return no_zero ? SUNTRUE : SUNFALSE;
}

// The fused operations go element by element (every input of element i is read before element i of an output is
// written), so an output may be any of the inputs, as the integrators allow. The sum runs in the order of the
// library's generic sequence of a scale and linear sums.
constexpr int kMaxFused = 16;

// z = sum_k c_k X_k.
int LinearCombination(int nvec, double* c, N_Vector* X, N_Vector z) {
  double* zd = data(z);
  const Index n = size(z);
  const double* x[kMaxFused];
  const int m = std::min(nvec, kMaxFused);
  for (int k = 0; k < m; ++k) x[k] = data(X[k]);
  for (Index i = 0; i < n; ++i) {
    double s = c[0] * x[0][i];
    for (int k = 1; k < m; ++k) s += c[k] * x[k][i];
    for (int k = m; k < nvec; ++k) s += c[k] * data(X[k])[i];
    zd[i] = s;
  }
  return 0;
}

// Z_k = a_k x + Y_k.
int ScaleAddMulti(int nvec, double* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  const double* xd = data(x);
  const Index n = size(x);
  if (nvec == 1) {
    LinearSum(a[0], x, 1.0, Y[0], Z[0]);
    return 0;
  }
  const double* y[kMaxFused];
  double* z[kMaxFused];
  const int m = std::min(nvec, kMaxFused);
  for (int k = 0; k < m; ++k) y[k] = data(Y[k]), z[k] = data(Z[k]);
  for (Index i = 0; i < n; ++i) {
    const double xi = xd[i];
    for (int k = 0; k < m; ++k) z[k][i] = a[k] * xi + y[k][i];
    for (int k = m; k < nvec; ++k) data(Z[k])[i] = a[k] * xi + data(Y[k])[i];
  }
  return 0;
}

}  // namespace

void UseCompiledVectorOps(N_Vector v) {
  N_Vector_Ops o = v->ops;
  o->nvlinearsum = LinearSum;
  o->nvconst = Const;
  o->nvprod = Prod;
  o->nvdiv = Div;
  o->nvscale = Scale;
  o->nvabs = Abs;
  o->nvinv = Inv;
  o->nvaddconst = AddConst;
  o->nvdotprod = DotProd;
  o->nvmaxnorm = MaxNorm;
  o->nvwrmsnorm = WrmsNorm;
  o->nvwrmsnormmask = WrmsNormMask;
  o->nvmin = Min;
  o->nvwl2norm = WL2Norm;
  o->nvl1norm = L1Norm;
  o->nvcompare = Compare;
  o->nvinvtest = InvTest;
  o->nvdotprodlocal = DotProd;
  o->nvmaxnormlocal = MaxNorm;
  o->nvminlocal = Min;
  o->nvl1normlocal = L1Norm;
  o->nvinvtestlocal = InvTest;
  o->nvwsqrsumlocal = WSqrSum;
  o->nvwsqrsummasklocal = WSqrSumMask;
  o->nvlinearcombination = LinearCombination;
  o->nvscaleaddmulti = ScaleAddMulti;
}

}  // namespace turbodyn
