#pragma once

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "trackphys/export.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// Eigen-decomposition of a symmetric 3x3 matrix: A = V diag(values) V^T.
struct SymmetricEigen3 {
    glm::dvec3 values;   ///< eigenvalues, sorted descending
    glm::dmat3 vectors;  ///< unit eigenvectors as columns, vectors[i] for values[i]
};

/// Cyclic Jacobi rotations (Golub & Van Loan, "Matrix Computations", 8.5): robust for
/// repeated and zero eigenvalues, orthonormal vectors to rounding, at most 32 sweeps
/// (converges in 4-6). Only the lower triangle of a is read. A matrix with NaN or inf
/// entries returns the identity basis with NaN values, never loops.
TRACKPHYS_API SymmetricEigen3 symmetric_eigen(const glm::dmat3& a);

}  // namespace trackphys
