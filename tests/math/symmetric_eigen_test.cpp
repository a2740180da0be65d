#include "trackphys/math/symmetric_eigen.hpp"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

namespace trackphys {
namespace {

// A = R diag(lambda) R^T with known eigenpairs, including repeated and zero eigenvalues.
TEST(SymmetricEigen, RecoversKnownEigenpairs) {
    std::mt19937_64 rng(2024);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> value(-10.0, 10.0);
    for (int i = 0; i < 20000; ++i) {
        const glm::dquat q =
            glm::normalize(glm::dquat(normal(rng), normal(rng), normal(rng), normal(rng)));
        const glm::dmat3 r = glm::mat3_cast(q);
        glm::dvec3 lambda(value(rng), value(rng), value(rng));
        if (i % 4 == 1) lambda.y = lambda.x;            // repeated pair
        if (i % 4 == 2) lambda = glm::dvec3(lambda.x);  // all equal
        if (i % 4 == 3) lambda.z = 0.0;                 // singular
        const glm::dmat3 a =
            r * glm::dmat3(lambda.x, 0, 0, 0, lambda.y, 0, 0, 0, lambda.z) * glm::transpose(r);

        const SymmetricEigen3 e = symmetric_eigen(a);
        const double scale =
            std::max({std::abs(lambda.x), std::abs(lambda.y), std::abs(lambda.z), 1.0});
        ASSERT_GE(e.values.x, e.values.y);
        ASSERT_GE(e.values.y, e.values.z);
        // Sorted values match the sorted inputs.
        glm::dvec3 sorted = lambda;
        if (sorted.x < sorted.y) std::swap(sorted.x, sorted.y);
        if (sorted.y < sorted.z) std::swap(sorted.y, sorted.z);
        if (sorted.x < sorted.y) std::swap(sorted.x, sorted.y);
        for (int k = 0; k < 3; ++k) {
            ASSERT_NEAR(e.values[k], sorted[k], 1e-12 * scale) << "case " << i;
            // A v = lambda v and the basis is orthonormal.
            const glm::dvec3 residual = a * e.vectors[k] - e.values[k] * e.vectors[k];
            ASSERT_LE(glm::length(residual), 1e-12 * scale) << "case " << i;
            ASSERT_NEAR(glm::length(e.vectors[k]), 1.0, 1e-13);
            ASSERT_NEAR(glm::dot(e.vectors[k], e.vectors[(k + 1) % 3]), 0.0, 1e-13);
        }
    }
}

TEST(SymmetricEigen, DiagonalZeroAndNonFiniteInputs) {
    const SymmetricEigen3 diagonal = symmetric_eigen(glm::dmat3(1, 0, 0, 0, 3, 0, 0, 0, 2));
    EXPECT_EQ(diagonal.values, glm::dvec3(3, 2, 1));
    EXPECT_EQ(std::abs(diagonal.vectors[0].y), 1.0);

    const SymmetricEigen3 zero = symmetric_eigen(glm::dmat3(0.0));
    EXPECT_EQ(zero.values, glm::dvec3(0.0));
    EXPECT_NEAR(glm::determinant(zero.vectors), 1.0, 0.0);

    const SymmetricEigen3 bad =
        symmetric_eigen(glm::dmat3(std::numeric_limits<double>::quiet_NaN()));
    EXPECT_TRUE(std::isnan(bad.values.x));
    EXPECT_EQ(bad.vectors, glm::dmat3(1.0));
}

}  // namespace
}  // namespace trackphys
