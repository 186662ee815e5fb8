#include "harness/jobs.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <stdexcept>
#include <thread>

extern char** environ;

#include "harness/report.h"
#include "harness/row_runner.h"

namespace fs = std::filesystem;

namespace gib {

unsigned resolve_jobs(unsigned requested, bool cpu_device) {
  if (requested) return requested;
  if (cpu_device) return std::max(1u, std::thread::hardware_concurrency());
  return kGpuJobs;
}

std::vector<std::string> split_devices(const std::string& device) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= device.size() && !device.empty()) {
    size_t comma = device.find(',', start);
    std::string d = device.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (d.empty()) throw std::invalid_argument(fmt::format("--device: expected D or D1,D2,... (indices or names), got '{}'", device));
    out.push_back(d);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

namespace {

// ------------------------------------------------------------------ worker side

// Writes one event per line to the parent.
class EventSink {
 public:
  explicit EventSink(int fd) : out_(fdopen(fd, "w")) {
    if (!out_) throw std::runtime_error("worker: cannot open the event stream");
  }
  void send(const nlohmann::json& e) {
    std::string line = e.dump() + "\n";
    std::fwrite(line.data(), 1, line.size(), out_);
    std::fflush(out_);
  }

 private:
  FILE* out_;
};

}  // namespace

int run_worker(const SuiteOptions& o) {
  // Events own stdout; anything else a stage prints goes to stderr.
  const int events_fd = dup(STDOUT_FILENO);
  dup2(STDERR_FILENO, STDOUT_FILENO);
  EventSink events(events_fd);
  SuiteSetup s = setup_suite(o, o.device);
  std::map<std::string, PlannedRow> plan;
  for (PlannedRow& p : plan_suite(s.cases)) plan[p.key] = p;
  RowRunner runner(*s.gpu, o, s.cases, s.tier, s.cache_root, s.suite);
  size_t errors_sent = 0;
  auto send_errors = [&] {
    for (; errors_sent < s.suite.case_errors.size(); ++errors_sent)
      events.send({{"e", "case_error"}, {"text", s.suite.case_errors[errors_sent]}});
  };
  std::string key;
  while (std::getline(std::cin, key)) {
    auto it = plan.find(key);
    if (it == plan.end()) {
      events.send({{"e", "end"}, {"key", key}, {"status", "error"}, {"messages", {"worker: no such row in the plan"}}});
      continue;
    }
    events.send({{"e", "start"}, {"key", key}});
    auto last = std::chrono::steady_clock::now();
    const ResultRow* row = runner.run(it->second, [&](const std::string& what, uint32_t d, uint32_t t) {
      auto now = std::chrono::steady_clock::now();
      if (d != t && now - last < std::chrono::milliseconds(100)) return;
      last = now;
      events.send({{"e", "frame"}, {"key", key}, {"what", what}, {"done", d}, {"total", t}});
    });
    send_errors();
    if (!row) {
      events.send({{"e", "end"}, {"key", key}, {"status", "error"}, {"messages", {"its case failed: see the case errors"}}});
      continue;
    }
    RowLine l = row_line(key, *row);
    events.send({{"e", "end"}, {"key", key}, {"status", l.status}, {"wall_s", l.wall_s}, {"figures", l.figures},
                 {"messages", l.messages}, {"row", row_to_json(*row)}});
  }
  runner.finish();
  send_errors();
  if (!s.suite.references.empty()) events.send({{"e", "references"}, {"references", s.suite.references}});
  return 0;
}

namespace {

// ------------------------------------------------------------------ parent side

struct Worker {
  unsigned index = 0;
  pid_t pid = -1;
  int to = -1, from = -1;  // its stdin, its stdout
  std::string buffer;      // a partial event line
  std::string current;     // the row it is rendering ("" idle)
  fs::path dir;
};

std::vector<std::string> worker_args(const SuiteOptions& o, const std::string& tier, const std::string& golden_class,
                                     const std::string& device, const fs::path& dir) {
  std::vector<std::string> a{"run", "--worker", "--profile", "full", "-j", "1", "--out", dir.string(),
                             "--cases-dir", o.cases_dir, "--goldens", o.goldens_dir, "--tier", tier,
                             "--golden-class", golden_class};
  if (!device.empty()) a.insert(a.end(), {"--device", device});
  if (!o.reference_cache.empty()) a.insert(a.end(), {"--reference-cache", o.reference_cache});
  if (!o.stability_scan) a.push_back("--no-stability-scan");
  a.insert(a.end(), {"--frames-per-submission", std::to_string(o.frames_per_submission)});
  if (o.validate) a.push_back("--validate");
  for (auto& g : o.case_globs) a.insert(a.end(), {"--case", g});
  for (auto& t : o.techniques) a.insert(a.end(), {"--technique", t});
  return a;
}

// The workers' environment: the parent's, with LP_NUM_THREADS set on a CPU device (lavapipe)
// unless the caller set it: `threads` rasteriser/compute threads per worker.
std::vector<std::string> worker_env(bool cpu_device, unsigned threads) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) env.emplace_back(*e);
  if (cpu_device && !std::getenv("LP_NUM_THREADS")) env.push_back(fmt::format("LP_NUM_THREADS={}", threads));
  return env;
}

// A GPU worker's environment: GIB_GPU_SUBMIT_LOCK names one lock file per device, so that the
// workers sharing a GPU submit one at a time (renderer/vk/submit_lock.h: without it they are
// time-sliced, wait through each other's slices and time each other's work). A lock the
// caller set is kept.
std::vector<std::string> with_submit_lock(std::vector<std::string> env, const std::string& device) {
  if (std::getenv("GIB_GPU_SUBMIT_LOCK")) return env;
  std::string name = device.empty() ? "default" : device;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  env.push_back(fmt::format("GIB_GPU_SUBMIT_LOCK={}", (fs::temp_directory_path() / ("gibench-gpu-" + name + ".lock")).string()));
  return env;
}

Worker spawn(unsigned index, const std::string& exe, const std::vector<std::string>& args,
             const std::vector<std::string>& env, const fs::path& dir) {
  int in[2], out[2];
  if (pipe2(in, O_CLOEXEC) != 0 || pipe2(out, O_CLOEXEC) != 0)
    throw std::runtime_error(fmt::format("-j: cannot create a pipe: {}", std::strerror(errno)));
  std::vector<char*> argv{const_cast<char*>(exe.c_str())};
  for (auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::vector<char*> envp;
  for (auto& e : env) envp.push_back(const_cast<char*>(e.c_str()));
  envp.push_back(nullptr);
  pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(fmt::format("-j: fork failed: {}", std::strerror(errno)));
  if (pid == 0) {
    dup2(in[0], STDIN_FILENO);
    dup2(out[1], STDOUT_FILENO);
    execve(exe.c_str(), argv.data(), envp.data());
    std::fprintf(stderr, "gibench: error: -j: cannot start the worker %s: %s\n", exe.c_str(), std::strerror(errno));
    _exit(127);
  }
  close(in[0]);
  close(out[1]);
  return Worker{index, pid, in[1], out[0], "", "", dir};
}

void send_row(Worker& w, const std::string& key) {
  std::string line = key + "\n";
  w.current = key;
  if (write(w.to, line.data(), line.size()) != ssize_t(line.size()))
    throw std::runtime_error(fmt::format("-j: worker {} stopped taking rows: {}", w.index, std::strerror(errno)));
}

// Moves a worker's images into the run's img/ (the same file from two workers: the same bytes).
void collect_images(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  if (!fs::is_directory(from, ec)) return;
  fs::create_directories(to);
  for (auto& f : fs::directory_iterator(from)) fs::rename(f.path(), to / f.path().filename());
}

std::string exit_text(int status) {
  if (WIFSIGNALED(status)) return fmt::format("was killed by signal {} ({})", WTERMSIG(status), strsignal(WTERMSIG(status)));
  return fmt::format("exited with status {}", WEXITSTATUS(status));
}

}  // namespace

JobsResult run_jobs(const SuiteOptions& o, const std::string& tier, const std::string& golden_class, bool cpu_device,
                    const std::vector<PlannedRow>& rows, unsigned jobs, SuiteProgress& progress) {
  JobsResult result;
  std::set<std::string> errors_seen;
  auto case_error = [&](const std::string& text) {
    if (errors_seen.insert(text).second) result.case_errors.push_back(text);
  };
  // The longest rows first, so that none starts last and runs alone.
  std::vector<PlannedRow> queue = rows;
  std::stable_sort(queue.begin(), queue.end(), [](auto& a, auto& b) { return a.cost > b.cost; });
  size_t next = 0;
  const std::vector<std::string> devices = split_devices(o.device);
  const fs::path jobs_dir = fs::path(o.out) / ".jobs";
  fs::remove_all(jobs_dir);
  signal(SIGPIPE, SIG_IGN);  // a worker that died is seen on its pipe, not by a signal
  const std::string exe = o.worker_exe.empty() ? fs::read_symlink("/proc/self/exe").string() : o.worker_exe;
  const unsigned cores_each = std::thread::hardware_concurrency() / std::max(1u, jobs);
  const std::vector<std::string> env = worker_env(cpu_device, cores_each > 1 ? cores_each : kCpuWorkerThreads);
  std::vector<Worker> workers;
  for (unsigned k = 0; k < jobs; ++k) {
    fs::path dir = jobs_dir / std::to_string(k);
    fs::create_directories(dir);
    const std::string device = devices.empty() ? "" : devices[k % devices.size()];
    workers.push_back(spawn(k, exe, worker_args(o, tier, golden_class, device, dir),
                            cpu_device ? env : with_submit_lock(env, device), dir));
  }
  auto feed = [&](Worker& w) {
    if (next < queue.size()) {
      send_row(w, queue[next++].key);
    } else if (w.to >= 0) {
      close(w.to);  // no more rows: the worker finishes and exits
      w.to = -1;
      w.current.clear();
    }
  };
  for (Worker& w : workers) feed(w);

  auto handle = [&](Worker& w, const std::string& line) {
    nlohmann::json e;
    try {
      e = nlohmann::json::parse(line);
    } catch (const std::exception&) {
      std::fprintf(stderr, "worker %u: %s\n", w.index, line.c_str());  // not an event: pass it on
      return;
    }
    const std::string type = e.value("e", "");
    if (type == "start") progress.started(e.value("key", ""));
    else if (type == "frame")
      progress.frame(e.value("key", ""), e.value("what", ""), e.value("done", 0u), e.value("total", 0u));
    else if (type == "case_error") case_error(e.value("text", ""));
    else if (type == "references") result.references.update(e["references"]);
    else if (type == "end") {
      if (e.contains("row")) result.rows.push_back(e["row"]);
      progress.finished({e.value("key", ""), e.value("status", "error"), e.value("wall_s", 0.0),
                         e.value("figures", ""), e.value("messages", std::vector<std::string>{})});
      feed(w);
    }
  };

  size_t alive = workers.size();
  while (alive) {
    std::vector<pollfd> fds;
    std::vector<Worker*> by_fd;
    for (Worker& w : workers)
      if (w.from >= 0) {
        fds.push_back({w.from, POLLIN, 0});
        by_fd.push_back(&w);
      }
    if (poll(fds.data(), fds.size(), 200) < 0 && errno != EINTR)
      throw std::runtime_error(fmt::format("-j: poll failed: {}", std::strerror(errno)));
    for (size_t i = 0; i < fds.size(); ++i) {
      if (!(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      Worker& w = *by_fd[i];
      char buf[65536];
      ssize_t n = read(w.from, buf, sizeof buf);
      if (n > 0) {
        w.buffer.append(buf, size_t(n));
        size_t nl;
        while ((nl = w.buffer.find('\n')) != std::string::npos) {
          std::string line = w.buffer.substr(0, nl);
          w.buffer.erase(0, nl + 1);
          handle(w, line);
        }
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      // End of its events: the worker has exited (or is about to).
      close(w.from);
      w.from = -1;
      if (w.to >= 0) close(w.to), w.to = -1;
      --alive;
      int status = 0;
      waitpid(w.pid, &status, 0);
      if (status != 0 || !w.current.empty()) {
        const std::string what = fmt::format("worker {} {}", w.index, exit_text(status));
        if (!w.current.empty()) {
          case_error(fmt::format("{}: {} while rendering {}", w.current.substr(0, w.current.find('/')), what, w.current));
          progress.finished({w.current, "error", 0, "", {what}});
          w.current.clear();
        } else {
          case_error(fmt::format("run: {}", what));
        }
      }
    }
    // Rows left when every worker has gone: nothing can render them.
    if (!alive)
      for (; next < queue.size(); ++next) {
        case_error(fmt::format("{}: not rendered: every worker process had exited", queue[next].key.substr(0, queue[next].key.find('/'))));
        progress.finished({queue[next].key, "error", 0, "", {"not rendered: every worker process had exited"}});
      }
  }
  for (Worker& w : workers) collect_images(w.dir / "img", fs::path(o.out) / "img");
  fs::remove_all(jobs_dir);
  return result;
}

}  // namespace gib
