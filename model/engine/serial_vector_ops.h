// Compiled vector kernels for SUNDIALS serial N_Vectors.
//
// The integrators spend a fixed share of every step in vector operations over the whole state (linear sums,
// weighted RMS norms for the error and convergence tests, the predictor's linear combinations). The library's
// own kernels are reached through the vector's table of operations, so a vector can carry others: these are
// plain loops over contiguous doubles, compiled with the project's optimisation, and the fused operations
// (linear combination, scale-add-multi) that the serial vector leaves switched off, so that CVODE's predictor,
// rescaling and interpolation make one pass over memory instead of one per term. Results are those of the
// library's kernels up to the order of summation in the reductions (dot products and norms), which is fixed
// here, so runs stay deterministic.
#pragma once

#include <nvector/nvector_serial.h>

namespace turbodyn {

/// Replaces the arithmetic operations of the serial vector v (from N_VNew_Serial) by compiled loops; vectors
/// cloned from v afterwards (N_VClone, and all of an integrator's internal vectors) inherit them.
void UseCompiledVectorOps(N_Vector v);

}  // namespace turbodyn
