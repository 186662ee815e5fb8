// Serialises the GPU submissions of several processes that share one GPU.
//
// Processes that submit to one GPU at once are time-sliced by the driver: their work never runs
// together, and a process that waits on its fence waits through the other processes' slices. The
// GPU timestamps of a command buffer then also count the other processes' work that ran inside
// its slices. Measured on an H200 with 8 `gibench run` workers at the GPU tier: a voxel-clipmap
// row whose frame takes 1.1 ms alone read 47 ms, and a 600-frame row that takes 3 s alone took
// 95 s. With this lock held from each submission to its fence, one process's work runs at a time:
// its timestamps count only its own work, and a wait ends when its own work does, while the
// other processes go on with their host work (metrics, image files).
//
// The lock is an exclusive flock(2) on the file $GIB_GPU_SUBMIT_LOCK names (the harness sets it
// for its workers, one file per GPU); without the variable nothing is locked.
#pragma once

namespace gib {

class SubmitGuard {
 public:
  SubmitGuard();  // blocks until this process holds the lock (no-op without the variable)
  explicit SubmitGuard(int fd);  // the same on a lock file open_lock opened (-1: no-op)
  ~SubmitGuard();
  // Opens (creating) a lock file; each open is its own holder, as each process's is.
  static int open_lock(const char* path);
  SubmitGuard(const SubmitGuard&) = delete;
  SubmitGuard& operator=(const SubmitGuard&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace gib
