// `soa view` and the viewer of `soa simulate --view`: a scene's state, a run or a trajectory
// file recorded by soa::view::Recorder (the library computes every frame) and written with
// soa::view::write() into a folder that opens from file:// (docs/viewer.md).
#include <csignal>
#include <filesystem>
#include <memory>

#include "output.hpp"
#include "trajectory.hpp"
#include "verbs.hpp"

namespace soa::cli {
namespace {

/// A message of soa::view::write() named after the option: "--out my_view: holds ...", or
/// "--out my_view: three.js not found: ..." for one that does not begin with the folder.
std::string named(const ViewOptions& opt, const std::string& message) {
  if (message.rfind(opt.dir + ":", 0) == 0) return opt.option + " " + message;
  return opt.option + " " + opt.dir + ": " + message;
}

}  // namespace

ViewWritten write_view(const Scene& scene, const ViewOptions& opt, soa::view::Recorder& rec,
                       const std::string& label, const std::string& note) {
  soa::view::View v = soa::view::view_of(scene);
  v.note = note;
  v.runs.push_back(rec.take(label));
  ViewWritten w;
  w.folder = opt.dir;
  w.label = label;
  w.note = note;
  w.frames = v.runs.back().frames.size();
  w.states = rec.offered();
  try {
    soa::view::write(v, opt.dir);
  } catch (const Error& e) {
    throw FileError(named(opt, e.what()));
  }
  return w;
}

void check_view_destination(const ViewOptions& opt) {
  try {
    soa::view::check_destination(opt.dir);
  } catch (const Error& e) {
    throw FileError(named(opt, e.what()));
  }
}

void emit_view(JsonWriter& w, const ViewWritten& v) {
  w.member("folder", v.folder);
  w.member("open", (std::filesystem::path(v.folder) / "index.html").string());
  w.member("run", v.label);
  w.member("frames", static_cast<long>(v.frames));
  w.member("states", v.states);
  w.member("note", v.note);
}

Result view(const Scene& scene, const State& x, bool given_state, const ViewOptions& opt,
            const std::optional<SimulationOptions>& sim,
            const std::optional<std::string>& trajectory) {
  if (sim) {  // simulate's run, its viewer, and a JSON of the viewer's
    Result r = simulate(scene, x, *sim, OutputOptions(), &opt, "view");
    const std::shared_ptr<const ViewWritten> written = r.view;
    const std::shared_ptr<const SimulationSummary> sum = r.summary;
    const double t_end = sim->t_end;
    const char* signal = signal_name(r.exit_code - 128);
    r.emit = [&scene, written, sum, t_end, signal](JsonWriter& w) {
      w.begin_object();
      w.member("scene", scene.title);
      w.member("source", "simulation");
      w.member("t_end", t_end);
      w.member("steps", sum->steps);
      if (sum->interrupted) {  // as simulate says it
        w.key("interrupted");
        w.begin_object();
        w.member("signal", signal);
        w.member("t", sum->t);
        w.end_object();
      }
      emit_view(w, *written);
      w.end_object();
    };
    return r;
  }
  std::shared_ptr<const ViewWritten> written;
  long rows = 0;
  if (trajectory) {
    // Read twice (read_trajectory()): the recorder is sized by the last time of the first
    // reading, and fed by the second; every row offered, the last one always kept.
    std::unique_ptr<soa::view::Recorder> rec;
    long seen = 0;
    set_stage("reading the trajectory " + *trajectory);
    read_trajectory(
        scene, *trajectory,
        [&](const TrajectoryInfo& info) {
          rows = info.rows;
          rec =
              std::make_unique<soa::view::Recorder>(scene, info.t_last, opt.frames, opt.quantities);
          set_stage("recording the viewer's frames of " + *trajectory);
        },
        [&](double t, const State& s) {
          rec->offer(t, s);
          if (++seen == rows) rec->record(t, s);
        });
    set_stage("writing the viewer");
    written = std::make_shared<const ViewWritten>(write_view(
        scene, opt, *rec, std::filesystem::path(*trajectory).filename().string(), rec->note()));
  } else {  // the state: one frame
    soa::view::Recorder rec(scene, 0.0, 2, opt.quantities);
    rec.record(0.0, x);
    set_stage("writing the viewer");
    written = std::make_shared<const ViewWritten>(
        write_view(scene, opt, rec, given_state ? "state of --q, --qd" : "state of the scene", ""));
  }
  Result r;
  r.view = written;
  const std::optional<std::string> file = trajectory;
  r.emit = [&scene, written, file, rows](JsonWriter& w) {
    w.begin_object();
    w.member("scene", scene.title);
    w.member("source", file ? "trajectory" : "state");
    if (file) {
      w.member("trajectory", *file);
      w.member("rows", rows);
    }
    emit_view(w, *written);
    w.end_object();
  };
  return r;
}

}  // namespace soa::cli
