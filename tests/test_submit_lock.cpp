// SubmitGuard (renderer/vk/submit_lock.h): while one process holds it, no other process can take
// the lock; it is free again once the holder's guard ends. Checked with a second process and
// non-blocking flock probes (no timing).
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include "renderer/vk/submit_lock.h"
#include "tests/temp_dir.h"

namespace gib {
namespace {

// Whether a fresh holder of the lock file could take it now (LOCK_NB), releasing it at once.
bool free_now(const std::string& path) {
  int fd = SubmitGuard::open_lock(path.c_str());
  const bool got = flock(fd, LOCK_EX | LOCK_NB) == 0;
  close(fd);  // closing the last descriptor of this open releases it
  return got;
}

TEST(SubmitGuard, ExcludesOtherProcessesWhileHeld) {
  test::TempDir dir;
  const std::string path = (dir.path() / "gpu.lock").string();
  EXPECT_TRUE(free_now(path));
  int to_child[2], from_child[2];
  ASSERT_EQ(pipe(to_child), 0);
  ASSERT_EQ(pipe(from_child), 0);
  pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    int code = 0;
    {
      SubmitGuard held(SubmitGuard::open_lock(path.c_str()));
      char c = 'h';
      if (write(from_child[1], &c, 1) != 1) code = 2;
      if (read(to_child[0], &c, 1) != 1) code = 3;  // held until the parent has probed
    }
    _exit(code);
  }
  char c = 0;
  ASSERT_EQ(read(from_child[0], &c, 1), 1);
  EXPECT_FALSE(free_now(path)) << "another process's guard is alive: the lock must be taken";
  c = 'r';
  ASSERT_EQ(write(to_child[1], &c, 1), 1);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_TRUE(free_now(path)) << "the holder's guard ended: the lock must be free";
  const int fd = SubmitGuard::open_lock(path.c_str());
  {
    SubmitGuard mine(fd);
    EXPECT_FALSE(free_now(path));
  }
  EXPECT_TRUE(free_now(path));
  close(fd);
}

TEST(SubmitGuard, NoLockFileIsNoLock) {
  SubmitGuard none(-1);  // must not block or throw
  SUCCEED();
}

TEST(SubmitGuard, UnopenableLockFileIsAClearError) {
  try {
    SubmitGuard::open_lock("/nonexistent-dir/gpu.lock");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/gpu.lock"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gib
