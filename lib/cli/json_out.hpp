// JSON output of `soa`: Eigen values as JSON arrays, and a printer that keeps vectors and
// matrix rows on one line each.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <ostream>

namespace soa::cli {

using Json = nlohmann::ordered_json;  // keeps keys in the order they are set

/// A vector as a JSON array.
template <class Derived>
Json to_json(const Eigen::MatrixBase<Derived>& x) {
  Json a = Json::array();
  for (Eigen::Index i = 0; i < x.size(); ++i) a.push_back(double(x(i)));
  return a;
}

/// A matrix as a JSON array of its rows.
template <class Derived>
Json rows_to_json(const Eigen::MatrixBase<Derived>& M) {
  Json a = Json::array();
  for (Eigen::Index r = 0; r < M.rows(); ++r) {
    Json row = Json::array();
    for (Eigen::Index c = 0; c < M.cols(); ++c) row.push_back(double(M(r, c)));
    a.push_back(std::move(row));
  }
  return a;
}

/// False when some number in \p j is NaN or infinite (nlohmann would print it as null).
bool all_finite(const Json& j);

/// Writes \p j indented by two spaces per level, with arrays of numbers or strings on one
/// line (so a 6-vector or a matrix row reads as one line), then a newline.
void write_json(std::ostream& out, const Json& j);

}  // namespace soa::cli
