#include "trackphys/math/symmetric_eigen.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace trackphys {

SymmetricEigen3 symmetric_eigen(const glm::dmat3& a) {
    // Work on a plain symmetric copy m[row][col]; glm is column-major, a[col][row].
    std::array<std::array<double, 3>, 3> m{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c <= r; ++c) m[r][c] = m[c][r] = a[c][r];
    std::array<std::array<double, 3>, 3> v{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};

    bool finite = true;
    for (const auto& row : m)
        for (double x : row) finite = finite && std::isfinite(x);
    if (!finite) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        return {glm::dvec3(nan), glm::dmat3(1.0)};
    }

    constexpr int max_sweeps = 32;
    for (int sweep = 0; sweep < max_sweeps; ++sweep) {
        const double off = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
        const double diagonal = m[0][0] * m[0][0] + m[1][1] * m[1][1] + m[2][2] * m[2][2];
        if (off <= 1e-36 * diagonal || off == 0.0) break;
        for (int p = 0; p < 2; ++p) {
            for (int q = p + 1; q < 3; ++q) {
                if (m[p][q] == 0.0) continue;
                // Rotation angle that zeroes m[p][q]: tan(2 theta) = 2 m_pq / (m_qq - m_pp),
                // taking the smaller root t = tan(theta) for stability.
                const double theta = (m[q][q] - m[p][p]) / (2.0 * m[p][q]);
                const double t = (theta >= 0.0 ? 1.0 : -1.0) /
                                 (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0);
                const double s = t * c;
                for (int k = 0; k < 3; ++k) {  // m <- m J (columns p, q)
                    const double mkp = m[k][p], mkq = m[k][q];
                    m[k][p] = c * mkp - s * mkq;
                    m[k][q] = s * mkp + c * mkq;
                }
                for (int k = 0; k < 3; ++k) {  // m <- J^T m (rows p, q)
                    const double mpk = m[p][k], mqk = m[q][k];
                    m[p][k] = c * mpk - s * mqk;
                    m[q][k] = s * mpk + c * mqk;
                }
                for (int k = 0; k < 3; ++k) {  // v <- v J
                    const double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
        }
    }

    std::array<int, 3> order = {0, 1, 2};
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2 - i; ++j)
            if (m[order[j]][order[j]] < m[order[j + 1]][order[j + 1]])
                std::swap(order[j], order[j + 1]);

    SymmetricEigen3 result;
    for (int i = 0; i < 3; ++i) {
        const int k = order[i];
        result.values[i] = m[k][k];
        result.vectors[i] = glm::dvec3(v[0][k], v[1][k], v[2][k]);
    }
    return result;
}

}  // namespace trackphys
