#include "distributed/job.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

#ifdef RAD_WITH_MPI
#include <mpi.h>
#endif

namespace rad {
namespace {

const Job* the_world = nullptr;

#ifdef RAD_WITH_MPI

/// mpirun stops the job's processes with SIGTERM when one of them died (or it was interrupted):
/// the root says so in one line (a signal handler may only write(2)). Its outputs are written
/// through temporary files renamed at the end (formats/atomic_file.h): none is half-written.
extern "C" void on_stopped_by_mpirun(int) {
  static const char kLine[] =
      "radiosity: error: stopped by mpirun (a process of the job died, or the job was "
      "interrupted); no output written\n";
  [[maybe_unused]] const ssize_t ignored = ::write(STDERR_FILENO, kLine, sizeof kLine - 1);
  ::_exit(1);
}

/// Tags of the block schedule's messages.
constexpr int kTagResult = 1;  ///< worker -> root: header + a block's bytes (or a failure)
constexpr int kTagAssign = 2;  ///< root -> worker: the next block, or -1 for "no more"

/// What a worker's message carries after its header.
enum class Kind : uint8_t { first_request = 0, result = 1, failure = 2 };

/// True when a launcher that speaks PMI started this process (Open MPI's mpirun sets the
/// first; MPICH's Hydra and Slurm's srun the others).
bool launched_by_mpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(name)) return true;
  }
  return false;
}

/// Sleeps a little longer each time it is called, up to 1 ms: waiting on MPI with a sleep
/// rather than in a blocking call, which in Open MPI spins a core that the threads of this or
/// another process on the node could use. Costs at most about 1 ms of latency per message.
class Backoff {
 public:
  void sleep() {
    std::this_thread::sleep_for(std::chrono::microseconds(micros_));
    micros_ = std::min(micros_ * 2, 1000);
  }

 private:
  int micros_ = 10;
};

void wait(MPI_Request& request) {
  Backoff backoff;
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    backoff.sleep();
  }
}

/// The bytes of one message, which MPI counts in int: larger strings go in pieces.
constexpr size_t kPiece = INT_MAX / 2;

void send(const std::string& bytes, int to, int tag) {
  MPI_Request request;
  MPI_Isend(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD,
            &request);
  wait(request);
}

std::string header(int64_t block, Kind kind) {
  std::string out(sizeof block + 1, '\0');
  std::memcpy(out.data(), &block, sizeof block);
  out[sizeof block] = static_cast<char>(kind);
  return out;
}

#endif

}  // namespace

Job::Job() = default;

Job::Job(int* argc, char*** argv) {
#ifdef RAD_WITH_MPI
  if (launched_by_mpirun()) {
    // FUNNELED: only the main thread calls MPI; the root's worker thread and TBB's never do.
    int provided = 0;
    MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
    joined_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    if (rank_ == 0 && size_ > 1) std::signal(SIGTERM, on_stopped_by_mpirun);
  }
#else
  (void)argc;
  (void)argv;
#endif
  the_world = this;
}

Job::~Job() {
  if (the_world == this) the_world = nullptr;
#ifdef RAD_WITH_MPI
  if (joined_) MPI_Finalize();
#endif
}

const Job& Job::alone() {
  static const Job one;
  return one;
}

const Job& Job::world() { return the_world ? *the_world : alone(); }

std::string Job::broadcast(std::string bytes) const {
  if (!distributed()) return bytes;
#ifdef RAD_WITH_MPI
  uint64_t size = bytes.size();
  MPI_Request request;
  MPI_Ibcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD, &request);
  wait(request);
  bytes.resize(size);
  for (size_t at = 0; at < size; at += kPiece) {
    const int piece = static_cast<int>(std::min<size_t>(kPiece, size - at));
    MPI_Ibcast(bytes.data() + at, piece, MPI_BYTE, 0, MPI_COMM_WORLD, &request);
    wait(request);
  }
#endif
  return bytes;
}

void Job::step(const std::function<void()>& step) const {
  if (!distributed()) {
    step();
    return;
  }
  std::string error;
  try {
    step();
  } catch (const AgreedFailure&) {
    throw;
  } catch (const std::exception& e) {
    error = e.what();
    if (error.empty()) error = "failed";
  }
#ifdef RAD_WITH_MPI
  // Every process's message to the root, which picks the verdict and sends it to all.
  const int length = static_cast<int>(error.size());
  std::vector<int> lengths(is_root() ? size_ : 0);
  MPI_Request request;
  MPI_Igather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
  wait(request);
  std::vector<int> offsets(lengths.size(), 0);
  for (size_t i = 1; i < lengths.size(); ++i) offsets[i] = offsets[i - 1] + lengths[i - 1];
  std::string all(is_root() ? static_cast<size_t>(offsets.back() + lengths.back()) : 0, '\0');
  MPI_Igatherv(error.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR,
               0, MPI_COMM_WORLD, &request);
  wait(request);
  std::string verdict;
  if (is_root()) {
    for (int r = 0; r < size_ && verdict.empty(); ++r) {
      if (lengths[r] == 0) continue;
      const std::string message = all.substr(offsets[r], lengths[r]);
      verdict = r == 0 ? message : "process " + std::to_string(r) + ": " + message;
    }
  }
  verdict = broadcast(verdict);
  if (!verdict.empty()) throw AgreedFailure(verdict, !is_root());
#endif
}

void Job::run_blocks(const BlockWork& work) const {
  if (!distributed()) {
    for (size_t b = 0; b < work.blocks; ++b) {
      work.compute(b);
      if (work.progress) work.progress(b + 1);
    }
    return;
  }
#ifdef RAD_WITH_MPI
  std::string verdict;
  if (is_root()) {
    std::atomic<size_t> next{0}, done{0};
    std::atomic<bool> stop{false}, local_finished{false};
    std::mutex failure_mutex;
    std::string failure;
    const auto fail = [&](const std::string& message) {
      const std::lock_guard lock(failure_mutex);
      if (failure.empty()) failure = message.empty() ? "failed" : message;
      stop = true;
    };
    // The root computes blocks too, on a thread that makes no MPI call (MPI_THREAD_FUNNELED).
    std::thread local([&] {
      for (size_t b; !stop && (b = next++) < work.blocks;) {
        try {
          work.compute(b);
          ++done;
        } catch (const std::exception& e) {
          fail(e.what());
        }
      }
      local_finished = true;
    });
    int active = size_ - 1;  // workers not yet told "no more"
    size_t reported = 0;
    Backoff backoff;
    while (active > 0 || !local_finished) {
      int flag = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, kTagResult, MPI_COMM_WORLD, &flag, &status);
      if (flag) {
        int count = 0;
        MPI_Get_count(&status, MPI_BYTE, &count);
        std::string message(static_cast<size_t>(count), '\0');
        MPI_Recv(message.data(), count, MPI_BYTE, status.MPI_SOURCE, kTagResult, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
        int64_t block = -1;
        std::memcpy(&block, message.data(), sizeof block);
        const auto kind = static_cast<Kind>(message[sizeof block]);
        const std::string_view payload = std::string_view(message).substr(sizeof block + 1);
        if (kind == Kind::result) {
          try {
            work.unpack(static_cast<size_t>(block), payload);
            ++done;
          } catch (const std::exception& e) {
            fail(e.what());
          }
        } else if (kind == Kind::failure) {
          fail("process " + std::to_string(status.MPI_SOURCE) + ": " + std::string(payload));
        }
        int64_t assign = -1;
        if (!stop) {
          const size_t b = next++;
          if (b < work.blocks) assign = static_cast<int64_t>(b);
        }
        if (assign < 0) --active;
        MPI_Request request;
        MPI_Isend(&assign, 1, MPI_INT64_T, status.MPI_SOURCE, kTagAssign, MPI_COMM_WORLD, &request);
        wait(request);
        backoff = Backoff();
      } else {
        backoff.sleep();
      }
      if (work.progress && done > reported) work.progress(reported = done);
    }
    local.join();
    verdict = failure;
  } else {
    std::string message = header(-1, Kind::first_request);
    for (;;) {
      send(message, 0, kTagResult);
      int64_t block = -1;
      MPI_Request request;
      MPI_Irecv(&block, 1, MPI_INT64_T, 0, kTagAssign, MPI_COMM_WORLD, &request);
      wait(request);
      if (block < 0) break;
      try {
        work.compute(static_cast<size_t>(block));
        message = header(block, Kind::result) + work.pack(static_cast<size_t>(block));
      } catch (const std::exception& e) {
        message = header(block, Kind::failure) + e.what();
      }
    }
  }
  verdict = broadcast(verdict);
  if (!verdict.empty()) throw AgreedFailure(verdict, !is_root());
#endif
}

void Job::finish() const {
#ifdef RAD_WITH_MPI
  if (!distributed()) return;
  if (is_root()) std::signal(SIGTERM, SIG_DFL);
  MPI_Request request;
  MPI_Ibarrier(MPI_COMM_WORLD, &request);
  wait(request);
#endif
}

void Job::abort(int code) const {
#ifdef RAD_WITH_MPI
  if (joined_) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::_Exit(code);
}

}  // namespace rad
