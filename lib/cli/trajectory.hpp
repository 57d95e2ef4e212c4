// Trajectory files of `soa`: the CSV that `simulate --out` writes and `view --trajectory`
// reads back. One header line, then one row per state:
//   t,q:NAME...,qd:NAME...,energy,quaternion_norm_error
// q and qd in file order (bodies base first, each hinge's coordinates in turn: "q:link3", or
// "q:ball[0]".."q:ball[3]" for a hinge of several), fields quoted as RFC 4180 says.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "soa/scene.hpp"

namespace soa::cli {

/// A CSV field as RFC 4180 writes it: quoted when it holds a comma, a quote or a line break,
/// quotes doubled.
std::string csv_field(const std::string& s);

/// The columns of a trajectory of \p scene, unquoted: "t", "q:..." per coordinate of theta
/// and "qd:..." per coordinate of beta in file order, "energy", "quaternion_norm_error".
std::vector<std::string> trajectory_columns(const Scene& scene);

/// What the first reading of a trajectory found (every row checked).
struct TrajectoryInfo {
  long rows = 0;      ///< data rows (the header not counted)
  double t_last = 0;  ///< the time of the last row
};

/// Reads the trajectory file \p path of \p scene twice: the first reading checks every row
/// and hands \p begin the count and the last time; the second hands \p row each state in
/// turn. Nothing reaches \p row unless the whole file is right. The header must be
/// trajectory_columns(scene) exactly; each row holds finite numbers, times that are >= 0 and
/// increase, and unit quaternions (within 1e-6, then normalized: theta_from_file_order()).
/// A file that is not a regular one (a pipe) is kept in memory between the readings.
/// Throws FileError "<path>: line 17, column \"qd:link3\": \"x\" is not a number"; the line
/// is the file's, counted from 1 (the header).
void read_trajectory(const Scene& scene, const std::string& path,
                     const std::function<void(const TrajectoryInfo&)>& begin,
                     const std::function<void(double t, const State& x)>& row);

}  // namespace soa::cli
