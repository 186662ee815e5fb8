#include "harness/report_check.h"

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace gib {
namespace {

namespace fs = std::filesystem;

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string shell_quote(const std::string& s) {
  std::string o = "'";
  for (char c : s) o += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return o + "'";
}

}  // namespace

std::string BrowserRun::describe() const {
  std::string s = "status '" + status + "', chromium exit " + std::to_string(exit_code) + ", log " + err_file;
  for (auto& l : page_console) s += "\n  " + l;
  return s;
}

std::string BrowserRun::problem() const {
  if (exit_code != 0) return fmt::format("chromium exited with {} (log {})", exit_code, err_file);
  if (status.rfind("error:", 0) == 0) return fmt::format("the page shows an error banner: {}", status);
  if (status != "ok")
    return fmt::format("the page never finished loading (status '{}'; log {})", status, err_file);
  if (!page_console.empty()) {
    std::string first = page_console.front();
    if (first.size() > 240) first = first.substr(0, 240) + "...";
    return fmt::format("{} console message(s) from the page, first: {} (log {})", page_console.size(), first,
                       err_file);
  }
  return "";
}

std::string find_chromium() {
  for (const char* name : {"chromium", "chromium-browser"}) {
    FILE* p = popen((std::string("command -v ") + name + " 2>/dev/null").c_str(), "r");
    if (!p) continue;
    char line[4096] = {0};
    std::string path = fgets(line, sizeof line, p) ? std::string(line) : std::string();
    pclose(p);
    while (!path.empty() && (path.back() == '\n' || path.back() == '\r')) path.pop_back();
    if (!path.empty()) return path;
  }
  return "";
}

BrowserRun run_chromium(const std::string& chromium, const std::string& dir_text, const std::string& screenshot) {
  const fs::path dir(dir_text);
  std::string templ = (fs::temp_directory_path() / "gib_report_profile_XXXXXX").string();
  std::vector<char> buf_dir(templ.begin(), templ.end());
  buf_dir.push_back('\0');
  if (!mkdtemp(buf_dir.data())) throw std::runtime_error("mkdtemp failed for " + templ);
  const fs::path profile(buf_dir.data());
  fs::path err_file = dir / (screenshot.empty() ? "chromium_dom.stderr" : "chromium_shot.stderr");
  std::string cmd = shell_quote(chromium) +
                    " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run"
                    " --disable-background-networking --disable-component-update --disable-sync"
                    " --user-data-dir=" + shell_quote(profile.string()) +
                    " --allow-file-access-from-files --virtual-time-budget=5000 --enable-logging=stderr --v=0";
  if (screenshot.empty())
    cmd += " --dump-dom";
  else
    cmd += " --hide-scrollbars --window-size=1400,2000 --screenshot=" + shell_quote(screenshot);
  cmd += " " + shell_quote("file://" + fs::absolute(dir / "index.html").string()) + " 2>" + shell_quote(err_file.string());

  BrowserRun r;
  r.err_file = err_file.string();
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) throw std::runtime_error("popen failed: " + cmd);
  char buf[65536];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  int st = pclose(p);
  r.exit_code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.err = read_all(err_file);
  std::error_code ec;
  fs::remove_all(profile, ec);

  const std::string key = "data-gib-status=\"";
  auto pos = r.out.find(key);
  if (pos != std::string::npos) {
    auto end = r.out.find('"', pos + key.size());
    r.status = r.out.substr(pos + key.size(), end - pos - key.size());
  }
  // Console messages are logged as `...:CONSOLE:<line>] "<message>", source: file:///...`
  // whatever their level; the report writes none unless something is wrong.
  std::istringstream lines(r.err);
  for (std::string line; std::getline(lines, line);)
    if ((line.find(":CONSOLE") != std::string::npos && line.find("source: file://") != std::string::npos) ||
        line.find("Uncaught") != std::string::npos)
      r.page_console.push_back(line);
  return r;
}

int cmd_check_report(const std::string& dir) {
  const std::string page = (fs::path(dir) / "index.html").string();
  auto fail = [&](const std::string& why) {
    fmt::print(stderr, "report {}: {}\n", page, why);
    return 1;
  };
  if (!fs::exists(page)) return fail("not found");
  const std::string chromium = find_chromium();
  if (chromium.empty()) return fail("cannot be checked: chromium is not on PATH (ci/setup.sh installs it)");
  BrowserRun r = run_chromium(chromium, dir);
  if (std::string why = r.problem(); !why.empty()) return fail(why);
  fmt::print("report {}: loads cleanly in headless Chromium (no error banner, no console output)\n", page);
  return 0;
}

}  // namespace gib
