#include "mjarm/sweep/slurm_backend.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "child_process.hpp"
#include "executable_on_path.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/interrupt.hpp"

namespace mjarm {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

/// What a Slurm tool printed and how it ended.
struct ToolRun {
  int status = -1;  ///< exit status; -1 when it did not exit (killed, timed out)
  std::string out, err;
};

std::string whole_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Runs Slurm tool @p args[0] (found on PATH) and waits up to @p seconds for it.
/// @throws Error when the tool is not on PATH or cannot start
ToolRun run_tool(std::vector<std::string> args, double seconds = 60.0) {
  const std::string path = executable_on_path(args[0]);
  if (path.empty())
    throw Error("'" + args[0] +
                "' is not on PATH: the Slurm backend needs Slurm's commands "
                "(run it on a login node of the cluster)");
  args[0] = path;
  char out_name[] = "/tmp/mjarm-slurm-out-XXXXXX";
  char err_name[] = "/tmp/mjarm-slurm-err-XXXXXX";
  const int out = ::mkstemp(out_name);
  const int err = ::mkstemp(err_name);
  ToolRun run;
  int error = 0;
  const pid_t pid = out < 0 || err < 0 ? -1 : start_child(args, {-1, out, err}, false, error);
  int status = 0;
  if (pid > 0 &&
      !wait_child_until(pid,
                        std::chrono::steady_clock::now() +
                            std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                std::chrono::duration<double>(seconds)),
                        status))
    status = kill_child(pid, false);
  if (pid > 0 && WIFEXITED(status)) run.status = WEXITSTATUS(status);
  run.out = whole_file(out_name);
  run.err = whole_file(err_name);
  for (const int fd : {out, err})
    if (fd >= 0) ::close(fd);
  ::unlink(out_name);
  ::unlink(err_name);
  if (pid < 0) throw Error("cannot start '" + path + "': " + std::strerror(error));
  return run;
}

/// The tool's stderr (or stdout), trimmed, for a message.
std::string said(const ToolRun& run) {
  std::string text = run.err.empty() ? run.out : run.err;
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text.empty() ? "(no message)" : text;
}

/// @p text quoted for bash: inside single quotes, a quote as '\''.
std::string quoted(const std::string& text) {
  std::string q = "'";
  for (const char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

void write_text(const fs::path& path, const std::string& text, const std::string& what) {
  FileWriter out(path, FileWriter::Mode::replace, what);
  out.write(text);
  out.commit();
}

fs::path slurm_dir(const SweepFolder& folder) { return fs::absolute(folder.dir) / "slurm"; }

/// The cluster's MaxArraySize (`scontrol show config`): an array's indices must be below it.
std::int64_t max_array_size() {
  const ToolRun run = run_tool({"scontrol", "show", "config"});
  if (run.status != 0) throw Error("scontrol show config failed: " + said(run));
  std::istringstream lines(run.out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("MaxArraySize", 0) != 0) continue;
    const auto eq = line.find('=');
    if (eq != std::string::npos) return std::atoll(line.c_str() + eq + 1);
  }
  throw Error("scontrol show config names no MaxArraySize");
}

std::string sbatch_header(const SweepPlan& plan, const SlurmOptions& o, const fs::path& logs) {
  std::string text = "#!/bin/bash\n#SBATCH --job-name=mjarm-sweep-" + plan.hash.substr(0, 8) +
                     "\n#SBATCH --cpus-per-task=" + std::to_string(o.cpus_per_task) +
                     "\n#SBATCH --time=" + o.time_limit +
                     "\n#SBATCH --output=" + (logs / "slurm-%A_%a.out").string() + "\n";
  if (!o.partition.empty()) text += "#SBATCH --partition=" + o.partition + "\n";
  if (!o.account.empty()) text += "#SBATCH --account=" + o.account + "\n";
  if (!o.qos.empty()) text += "#SBATCH --qos=" + o.qos + "\n";
  return text;
}

/// Submits @p script with the options' pass-through arguments and @p extra: the job's id.
std::string submit(const fs::path& script, const SlurmOptions& o,
                   const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{"sbatch", "--parsable"};
  args.insert(args.end(), o.sbatch_args.begin(), o.sbatch_args.end());
  args.insert(args.end(), extra.begin(), extra.end());
  args.push_back(script.string());
  const ToolRun run = run_tool(args);
  std::string id = run.out.substr(0, run.out.find_first_of(";\n"));
  if (run.status != 0 || id.empty())
    throw Error("sbatch " + script.filename().string() + " failed (exit " +
                std::to_string(run.status) + "): " + said(run));
  return id;
}

std::vector<std::string> recorded_jobs(const SweepFolder& folder) {
  const fs::path file = slurm_dir(folder) / "jobs.json";
  std::vector<std::string> ids;
  std::error_code ec;
  if (!fs::exists(file, ec)) return ids;
  const std::string text = whole_file(file);
  if (!Json::accept(text)) throw Error(file.string() + ": not valid JSON (damaged?)");
  const Json doc = Json::parse(text);
  for (const Json& id : doc.value("jobs", Json::array())) ids.push_back(id.get<std::string>());
  if (doc.contains("merge") && doc["merge"].is_string())
    ids.push_back(doc["merge"].get<std::string>());
  return ids;
}

}  // namespace

SlurmSubmission submit_sweep_slurm(const SweepFolder& folder, const SweepPlan& plan,
                                   const SlurmOptions& o) {
  if (o.executable.empty() || !o.executable.is_absolute())
    throw Error("slurm: the mjarm the tasks run must be an absolute path, got '" +
                o.executable.string() + "'");
  if (o.cpus_per_task < 1 || o.throttle < 0)
    throw Error("slurm: cpus per task must be ≥ 1 and the throttle ≥ 0");
  const ShardStates states = shard_states(folder, plan);
  const std::vector<std::int64_t> to_run = states.to_run();
  if (to_run.empty())
    throw Error("every shard of '" + folder.dir.string() + "' is done: nothing to submit");

  SlurmSubmission submission;
  submission.max_array_size = max_array_size();
  if (submission.max_array_size < 1)
    throw Error("slurm: MaxArraySize is " + std::to_string(submission.max_array_size));
  const fs::path dir = slurm_dir(folder);
  const fs::path logs = dir / "logs", exits = dir / "exit";
  std::error_code ec;
  fs::create_directories(logs, ec);
  fs::create_directories(exits, ec);
  if (ec) throw Error("cannot create '" + logs.string() + "': " + ec.message());
  const std::string sweep_dir = fs::absolute(folder.dir).string();

  // one array per MaxArraySize shards: a task's shard is the line of its index in a list
  const auto chunk = static_cast<std::size_t>(submission.max_array_size);
  for (std::size_t first = 0, k = 0; first < to_run.size(); first += chunk, ++k) {
    const std::size_t count = std::min(chunk, to_run.size() - first);
    const fs::path list = dir / ("array-" + std::to_string(k) + ".shards");
    std::string lines;
    for (std::size_t i = first; i < first + count; ++i) lines += std::to_string(to_run[i]) + "\n";
    write_text(list, lines, "shard list");
    const fs::path script = dir / ("array-" + std::to_string(k) + ".sbatch");
    std::string text = sbatch_header(plan, o, logs);
    text += "#SBATCH --array=0-" + std::to_string(count - 1) +
            (o.throttle > 0 ? "%" + std::to_string(o.throttle) : std::string()) + "\n";
    text += "shard=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" " + quoted(list.string()) + ")\n";
    text += quoted(o.executable.string()) + " sweep shard " + quoted(sweep_dir) +
            " --index \"$shard\" > " + quoted((logs / "shard-").string()) + "\"$shard.log\" 2>&1\n";
    text += "status=$?\necho \"$status\" > " + quoted((exits / "shard-").string()) +
            "\"$shard.txt\"\nexit \"$status\"\n";
    write_text(script, text, "sbatch script");
    submission.scripts.push_back(script);
  }
  const fs::path merge = dir / "merge.sbatch";
  write_text(merge,
             sbatch_header(plan, o, logs) + quoted(o.executable.string()) + " sweep merge " +
                 quoted(sweep_dir) + " --require-complete\n",
             "sbatch script");
  submission.scripts.push_back(merge);
  submission.shards = static_cast<std::int64_t>(to_run.size());
  if (o.dry_run) return submission;

  // all or nothing: a failed submission cancels the jobs submitted before it
  try {
    for (std::size_t k = 0; k + 1 < submission.scripts.size(); ++k)
      submission.jobs.push_back(submit(submission.scripts[k], o));
    std::string after = "--dependency=afterany";
    for (const std::string& id : submission.jobs) after += ":" + id;
    submission.merge_job =
        submit(merge, o, {after, "--output=" + (logs / "merge-%j.out").string()});
  } catch (const Error&) {
    for (const std::string& id : submission.jobs) run_tool({"scancel", id});
    throw;
  }
  Json jobs{{"jobs", submission.jobs}, {"merge", submission.merge_job}};
  write_text(dir / "jobs.json", jobs.dump(1) + "\n", "job list");
  return submission;
}

std::vector<SlurmJob> slurm_jobs(const SweepFolder& folder) {
  const std::vector<std::string> ids = recorded_jobs(folder);
  std::vector<SlurmJob> jobs;
  if (ids.empty()) return jobs;
  std::string list;
  for (const std::string& id : ids) list += (list.empty() ? "" : ",") + id;
  const ToolRun run = run_tool({"squeue", "-h", "-r", "-j", list, "-o", "%i %T"});
  // squeue refuses ids it no longer knows ("Invalid job id specified"): they have ended
  if (run.status != 0 && run.err.find("Invalid job id") == std::string::npos)
    throw Error("squeue failed: " + said(run));
  std::istringstream lines(run.out);
  for (std::string id, state; lines >> id >> state;) jobs.push_back({id, state});
  return jobs;
}

void cancel_slurm_jobs(const SweepFolder& folder) {
  const std::vector<std::string> ids = recorded_jobs(folder);
  if (ids.empty()) return;
  std::vector<std::string> args{"scancel"};
  args.insert(args.end(), ids.begin(), ids.end());
  const ToolRun run = run_tool(args);
  if (run.status != 0) throw Error("scancel failed: " + said(run));
}

bool wait_for_slurm_jobs(const SweepFolder& folder, const SweepPlan& plan,
                         const std::function<void(std::int64_t)>& progress) {
  while (true) {
    if (interrupt_requested()) return false;
    const bool running = !slurm_jobs(folder).empty();
    if (progress) progress(static_cast<std::int64_t>(shard_states(folder, plan).done.size()));
    if (!running) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
}

std::string slurm_shard_failure(const SweepFolder& folder, std::int64_t index) {
  const fs::path dir = slurm_dir(folder);
  const std::string name = "shard-" + std::to_string(index);
  std::error_code ec;
  const fs::path exit_file = dir / "exit" / (name + ".txt"), log = dir / "logs" / (name + ".log");
  if (!fs::exists(exit_file, ec) && !fs::exists(log, ec))
    return "shard " + std::to_string(index) +
           ": no task ran it to the end (cancelled, or never started)";
  std::string status = fs::exists(exit_file, ec) ? whole_file(exit_file) : "?";
  while (!status.empty() && status.back() == '\n') status.pop_back();
  std::string text = whole_file(log);
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const auto last = text.rfind('\n');
  return "shard " + std::to_string(index) + " exited with " + status + ": " +
         (last == std::string::npos ? text : text.substr(last + 1)) + " (" + log.string() + ")";
}

}  // namespace mjarm
