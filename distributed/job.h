#pragma once
/// The processes of an MPI job. `mpirun -n N radiosity render|probe|sweep ...` splits one
/// command's work over N processes, each with its own threads: the root (rank 0) reads the
/// inputs once and broadcasts them, every process parses the same bytes, blocks of work (tiles
/// of pixels, runs of probe points) are handed out as processes free up, and the root gathers
/// the results and writes the outputs. Started without mpirun, a process is a job of one and
/// nothing here touches MPI. Built without MPI (RAD_MPI=OFF), every job is a job of one.
///
/// Failures: a step that fails on any process fails on all of them (`step`, `run_blocks`): the
/// root reports it in one line and every process exits 1. A process that dies is mpirun's to
/// notice: it ends the whole job (no process waits forever), and the outputs, written by the
/// root only after all results are in, stay as they were.
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

#include "scene/error.h"

namespace rad {

/// A command's work cut into blocks, each computed by one process into its own slots.
struct BlockWork {
  size_t blocks = 0;
  /// Computes block b into this process's slots (it may use all of the process's threads).
  std::function<void(size_t block)> compute;
  /// Block b's slots as bytes, on the process that computed it.
  std::function<std::string(size_t block)> pack;
  /// Stores block b's bytes into the root's slots. Called on the root's main thread, while the
  /// root's own worker computes other blocks (disjoint slots).
  std::function<void(size_t block, std::string_view bytes)> unpack;
  /// On the root (may be empty): the number of blocks done so far.
  std::function<void(size_t done)> progress;
};

/// A failure that every process of the job has agreed on. The root's message is the one line
/// to print; on the other processes it is `quiet`: they exit 1 without a word.
class AgreedFailure : public Error {
 public:
  AgreedFailure(const std::string& message, bool quiet) : Error(message), quiet_(quiet) {}
  bool quiet() const { return quiet_; }

 private:
  bool quiet_;
};

class Job {
 public:
  /// Joins the MPI job when mpirun (or another PMI launcher) started this process; otherwise,
  /// or without MPI, a job of one. The job made here is the one `world()` returns.
  Job(int* argc, char*** argv);
  ~Job();
  Job(const Job&) = delete;
  Job& operator=(const Job&) = delete;

  /// The job main() made; a job of one if none was made (tests, tools).
  static const Job& world();
  /// A job of one process: for work that only the root does.
  static const Job& alone();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }
  /// True when there is more than one process.
  bool distributed() const { return size_ > 1; }

  /// The root's `bytes`, on every process (the others' argument is ignored).
  std::string broadcast(std::string bytes) const;

  /// Runs `step` on every process. If it throws on any of them, every process throws an
  /// AgreedFailure: the root's own message when the root failed, else "process K: message" of
  /// the first process that did. In a job of one, `step` runs as it is and its exceptions pass.
  void step(const std::function<void()>& step) const;

  /// Computes every block exactly once, on some process: the root hands out block numbers as
  /// processes ask for them (a dynamic schedule: uneven blocks leave no process idle while
  /// blocks remain) and computes blocks itself on a thread of its own; results are unpacked on
  /// the root. Which process computed a block is not seen in the result. A block that throws
  /// ends the schedule and, as `step`, fails on every process. In a job of one, the blocks are
  /// computed in order and nothing is packed.
  void run_blocks(const BlockWork& work) const;

  /// The end of the job's work: returns when every process has called it (waiting without
  /// spinning a core). From here on, mpirun stopping this process is no failure of the work.
  void finish() const;

  /// Ends every process of the job with `code` at once (a failure not agreed on: the others
  /// may be waiting for this process).
  [[noreturn]] void abort(int code) const;

 private:
  Job();  // a job of one
  int rank_ = 0;
  int size_ = 1;
  bool joined_ = false;  ///< MPI_Init was called here
};

}  // namespace rad
