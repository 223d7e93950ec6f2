// Measuring in a fresh child process: its own heap, OpenMP thread pool and peak-memory count.
// Shared by the benchmarks that report peak memory (bench_scaling, bench_thread_scaling).
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>

namespace meshik_bench {

// The process's peak resident memory so far, in MB.
inline double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // kilobytes on Linux
}

// The resident memory now (MB; Linux: the second field of /proc/self/statm, in pages), or -1.
inline double current_rss_mb() {
  std::FILE* statm = std::fopen("/proc/self/statm", "r");
  if (statm == nullptr) return -1.0;
  long size = 0, resident = -1;
  const bool read = std::fscanf(statm, "%ld %ld", &size, &resident) == 2;
  std::fclose(statm);
  return read ? resident * (sysconf(_SC_PAGESIZE) / 1048576.0) : -1.0;
}

// Runs work() (returning a trivially copyable T) in a child process and stores what it returned in
// `result`; returns whether the child succeeded. The parent should never start OpenMP itself (a
// pool does not survive fork).
template <typename T, typename Work>
bool in_child(const Work& work, T& result) {
  int channel[2];
  if (pipe(channel) != 0) return false;
  const pid_t child = fork();
  if (child == 0) {
    close(channel[0]);
    const T value = work();
    const ssize_t sent = write(channel[1], &value, sizeof value);
    _exit(sent == static_cast<ssize_t>(sizeof value) ? 0 : 1);
  }
  close(channel[1]);
  size_t got = 0;
  for (ssize_t n; got < sizeof result && (n = read(channel[0], reinterpret_cast<char*>(&result) + got,
                                                     sizeof result - got)) > 0;)
    got += static_cast<size_t>(n);
  close(channel[0]);
  int status = 0;
  waitpid(child, &status, 0);
  return got == sizeof result && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

}  // namespace meshik_bench
