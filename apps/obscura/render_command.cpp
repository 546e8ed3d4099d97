// `obscura render`: renders every sensor of a scene into an output folder,
// at one time or over a sequence (sequence/sequence_runner.h), and writes the
// images, time series, screening metrics and summary (report/sequence_output.h).
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.h"
#include "format_option.h"
#include "memory_option.h"
#include "obscura/core/byte_stream.h"
#include "obscura/core/check.h"
#include "obscura/core/error.h"
#include "obscura/core/interrupt.h"
#include "obscura/gpu/gpu_device.h"
#include "obscura/io/provenance.h"
#include "obscura/report/sequence_output.h"
#include "obscura/report/sequence_resume.h"
#include "obscura/sequence/sequence_runner.h"
#include "progress_printer.h"

namespace obscura::cli {
namespace {

void warn_about_blind_sensors(const std::vector<TargetMask>& masks) {
  std::string blind;
  for (const TargetMask& m : masks)
    if (m.empty()) blind += (blind.empty() ? "" : ", ") + m.sensor;
  if (!blind.empty())
    std::cerr << fmt::format(
        "obscura: warning: no target pixel in view of sensor {}: its screening metrics are empty "
        "(null)\n",
        blind);
}

// A sequence that fails part-way keeps every frame that completed (each was
// written whole) and records the failure and those frames in summary.json;
// the error still ends the run (exit 1, or 130/143 after SIGINT/SIGTERM),
// now saying what was kept.
SequenceResult render_or_keep_frames(Scene& scene, const std::vector<double>& times,
                                     const SequenceOptions& options, SequenceWriter& writer) {
  try {
    return render_sequence(scene, times, options);
  } catch (const Error& e) {
    if (writer.frames_done().empty()) throw;
    writer.finish_failed(e.what());
    const std::string kept = fmt::format(
        " (kept the {} completed frames {}–{}{} and summary.json in {})",
        writer.frames_done().size(), writer.frames_done().front(), writer.frames_done().back(),
        writer.netcdf_kept() ? ", render.nc" : "", writer.dir().string());
    if (const auto* stop = dynamic_cast<const Interrupted*>(&e))
      throw Interrupted(stop->signal(), kept);
    if (const auto* input = dynamic_cast<const InputError*>(&e))
      throw InputError(input->file(), input->field(), input->detail() + kept);
    if (dynamic_cast<const InternalError*>(&e)) throw;
    throw Error(e.what() + kept);
  }
}

// Rank 0's list of completed frames, on every rank.
std::vector<std::size_t> share_completed_frames(const ProcessGroup& processes,
                                                const std::vector<std::size_t>& frames) {
  ByteWriter out;
  out.put_vector(frames);
  const std::string bytes = processes.broadcast(out.take());
  ByteReader in(bytes);
  return in.get_vector<std::size_t>();
}

// One line per frame (or share of a frame) a rank has rendered, for runs
// shared among MPI ranks, where one rewritten progress line would mix ranks.
void print_rendered(const FrameRendered& r) {
  std::cerr << fmt::format("obscura: rank {}/{}: {} {}/{} (t = {:.4g} s) in {:.1f} s\n", r.rank,
                           r.ranks, r.by_tiles ? "rows of frame" : "frame", r.frame + 1, r.frames,
                           r.time_s, r.seconds);
}

}  // namespace

Command add_render_command(CLI::App& app, const Invocation& invocation) {
  auto* cmd = app.add_subcommand("render", "Render every sensor of a scene file");
  struct Options {
    std::string scene;
    std::string output;
    std::optional<int> threads;
    std::optional<std::uint64_t> seed;
    double at = 0.0;
    std::string time_range;
    std::string share = "auto";
    std::optional<std::string> device;
    bool json = false, resume = false;
    std::vector<std::string> formats;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("scene", o->scene, "Scene file (JSON, docs/formats.md)")->required();
  cmd->add_option("-o,--output", o->output, "Output folder (created if missing)")->required();
  cmd->add_option("--threads", o->threads,
                  "Worker threads (per MPI rank; default: the scene's, 0 = all cores)")
      ->check(CLI::Range(0, 4096));
  cmd->add_option("--seed", o->seed, "Random seed for pixel jitter (default: the scene's)");
  auto* at = cmd->add_option("--at", o->at, "Scene time to render, seconds (default 0)");
  cmd->add_option("--time", o->time_range,
                  "Render a frame sequence at times A:B:STEP (seconds): numbered EXR and PNG files "
                  "per frame, time_series.csv with region means, contact_sheet.png, and with a "
                  "target surface screening metrics and their plots (docs/metrics.md)")
      ->excludes(at);
  cmd->add_option("--share", o->share,
                  "Under mpirun, how ranks share the work: frames (every N-th frame each), tiles "
                  "(every N-th row of each frame, and its photons) or auto (frames when there are "
                  "at least as many frames as ranks); outputs are the same bits whatever the "
                  "choice (docs/cluster.md)")
      ->check(CLI::IsMember({"auto", "frames", "tiles"}))
      ->capture_default_str();
  cmd->add_option("--device", o->device,
                  "Where the camera march runs: cpu, or gpu (a CUDA build; emission-absorption and "
                  "radiance-cache over a cloud that is one voxel grid, docs/gpu.md) (default: the "
                  "scene's \"device\", else cpu)")
      ->check(CLI::IsMember({"cpu", "gpu"}));
  cmd->add_flag("--resume", o->resume,
                "Continue a --time sequence that stopped part-way in the output folder: the "
                "frames it completed are read back, not rendered again (the same scene, inputs, "
                "seed and times only)");
  cmd->add_flag("--json", o->json, "Print a JSON summary on stdout");
  add_format_option(cmd, o->formats);
  auto max_memory = std::make_shared<std::string>();
  add_max_memory_option(cmd, max_memory);
  return {cmd, [o, invocation, max_memory]() {
            const ProcessGroup& processes = *invocation.processes;
            const bool root = processes.is_root();
            apply_max_memory(*max_memory);
            // Cheap checks of the command line first, before reading any file.
            if (!std::isfinite(o->at))
              throw InputError("", "--at", "must be a finite time in seconds");
            const bool sequence = !o->time_range.empty();
            if (o->resume && !sequence)
              throw InputError("", "--resume", "continues a --time sequence; give --time");
            const std::vector<double> times =
                sequence ? parse_time_range(o->time_range) : std::vector<double>{o->at};
            // Every rank loads the scene; rank 0 alone makes the output folder.
            // A failure is shared, so that rank 0 reports it once.
            Scene scene;
            std::optional<SequenceWriter> writer;
            std::vector<std::size_t> completed;  // by an earlier run (--resume)
            run_together(processes, [&] {
              scene = load_scene(o->scene);
              if (o->threads) scene.settings.threads = *o->threads;
              if (o->seed) scene.settings.seed = *o->seed;
              apply_formats(o->formats, scene);
              if (o->device) {
                scene.settings.device = *parse_render_device(*o->device);
                check_render_settings(scene.settings, [](std::string_view, std::string_view what) {
                  return InputError("", "--device", std::string(what));
                });
              }
              // Before any output: a GPU asked for where there is none is an error now.
              if (scene.settings.device == RenderDevice::kGpu) require_gpu();
              if (!root) return;
              Provenance provenance =
                  make_provenance(invocation.command_line, scene.settings.seed, scene.input_files);
              if (o->resume) completed = completed_frames(o->output, scene, times, provenance);
              writer.emplace(o->output, scene, times, sequence, std::move(provenance),
                             std::filesystem::path(o->scene).filename().string());
            });
            if (o->resume) completed = share_completed_frames(processes, completed);
            if (root && !completed.empty()) {
              std::cerr << fmt::format(
                  "obscura: resuming: {} of {} frames are complete in {}; rendering the rest\n",
                  completed.size(), times.size(), o->output);
              writer->record_resumed(completed);
            }
            ProgressPrinter progress(scene, sequence);
            SequenceOptions options;
            options.processes = &processes;
            options.sharing = parse_work_sharing(o->share);
            if (processes.size() > 1)
              options.on_rendered = print_rendered;
            else
              options.progress = [&](const RenderProgress& p) { progress.update(p); };
            options.on_masks = warn_about_blind_sensors;
            options.on_warning = [&](const std::string& w) {
              progress.finish();  // the warning on a line of its own
              std::cerr << "obscura: warning: " << w << "\n";
            };
            options.on_frame = [&](const RenderedFrame& frame) { writer->write_frame(frame); };
            options.completed = completed;
            options.load_completed = [&](std::size_t f) {
              return read_completed_frame(o->output, scene, f, times[f]);
            };
            if (!root) {
              render_sequence(scene, times, options);
              run_together(processes, [] {});  // rank 0 writes what remains
              return 0;
            }
            const SequenceResult result = render_or_keep_frames(scene, times, options, *writer);
            progress.finish();
            run_together(processes, [&] { writer->finish(result); });
            if (o->json) {
              nlohmann::json summary = writer->summary();
              summary.erase("scene");
              std::cout << summary.dump(2) << "\n";
            } else {
              std::cout << sequence_summary_text(*writer);
            }
            return 0;
          }};
}

}  // namespace obscura::cli
