// Opens a written report (DIR/index.html) in headless Chromium and says whether it loaded
// cleanly: the page sets body[data-gib-status] to "ok" once everything rendered and every image
// loaded, or "error: <what>" (the error banner) on a failed image or a script error; Chromium's
// log shows any console output from the page (the report writes none unless something is
// wrong). Used by tests/test_report.cpp and by `gibench check-report` (ci/suite.sh).
#pragma once
#include <string>
#include <vector>

namespace gib {

struct BrowserRun {
  int exit_code = -1;
  std::string out, err;                   // --dump-dom output; Chromium's log (stderr)
  std::string status;                     // data-gib-status, "" when absent
  std::vector<std::string> page_console;  // log lines with console output from the page
  std::string err_file;                   // where the full log was written
  // For failure messages: the status, the page's console lines and where the full log is.
  std::string describe() const;
  // "" when the page loaded cleanly (exit 0, status "ok", no console output); else one line.
  std::string problem() const;
};

// The chromium binary on PATH ("chromium" or "chromium-browser"), "" when there is none.
std::string find_chromium();

// One headless Chromium run on dir/index.html: --dump-dom, or a screenshot when `screenshot`
// is not empty. The log goes to dir/chromium_dom.stderr (chromium_shot.stderr).
BrowserRun run_chromium(const std::string& chromium, const std::string& dir, const std::string& screenshot = "");

// `gibench check-report DIR`: 0 when DIR/index.html loads cleanly; otherwise one line on stderr
// ("report DIR/index.html: ...") and 1.
int cmd_check_report(const std::string& dir);

}  // namespace gib
