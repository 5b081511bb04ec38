#include "hmi/machine_mover.h"

#include <cstdio>
#include <fstream>
#include <thread>

namespace lcnc::hmi {
namespace {

constexpr auto kPoll = std::chrono::milliseconds(2);

Diagnostic fail(const std::string& what) { return make_error(ErrorCode::RtRefused, what); }

}  // namespace

MachineMover::MachineMover(std::string shm_name, std::filesystem::path dir)
    : link_(std::move(shm_name)), dir_(std::move(dir)) {}

bool MachineMover::wait_link(std::chrono::steady_clock::time_point deadline) {
  while (!link_.poll()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(kPoll);
  }
  return true;
}

Result<shm::JobStatus> MachineMover::command(shm::CommandType type, const std::string& text,
                                             std::chrono::steady_clock::time_point deadline) {
  const std::uint32_t seq = link_.send(type, 0.0, 0, text);
  if (seq == 0) return fail("the daemon's command queue is full or the link is lost");
  for (;;) {
    if (!link_.poll()) return fail("link to lasercncd lost: " + link_.why());
    // its own answer slot: another sender's command in between never hides it
    if (const std::optional<shm::Answer> a = link_.answer(seq)) {
      if (a->code != 0) return Diagnostic{static_cast<ErrorCode>(a->code), {}, 0, 0, a->message};
      const std::optional<shm::JobStatus> job = link_.job();
      if (job) return *job;
    }
    if (std::chrono::steady_clock::now() > deadline) return fail("no answer from lasercncd");
    std::this_thread::sleep_for(kPoll);
  }
}

Result<Pose> MachineMover::position() {
  if (!wait_link(std::chrono::steady_clock::now() + MachineLink::kLostAfter))
    return fail("no link to lasercncd: " + link_.why());
  const std::optional<shm::Status> st = link_.status();
  if (!st) return fail("no status from lasercncd");
  Pose p;
  for (int i = 0; i < kAxisCount; ++i) p[i] = st->pos[i];
  return p;
}

Status MachineMover::move_to(const Pose& target, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  if (!wait_link(deadline)) return fail("no link to lasercncd: " + link_.why());
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  const std::filesystem::path prog = dir_ / ("move_" + std::to_string(++moves_ % 2) + ".ngc");
  {
    std::ofstream f(prog, std::ios::binary | std::ios::trunc);
    char line[256];
    std::snprintf(line, sizeof line, "G21 G90 G0 X%.4f Y%.4f Z%.4f A%.4f C%.4f\n", target[0], target[1],
                  target[2], target[3], target[5]);
    f << "(an HMI workflow's move)\n" << line << "M2\n";
    if (!f) return fail("cannot write " + prog.string());
  }
  const std::optional<shm::JobStatus> before = link_.job();
  if (!before) return fail("no job status from lasercncd");
  if (Result<shm::JobStatus> r = command(shm::CommandType::Load, prog.string(), deadline); !r)
    return r.error();
  if (Result<shm::JobStatus> r = command(shm::CommandType::Start, {}, deadline); !r) return r.error();
  for (;;) {
    if (!link_.poll()) return fail("link to lasercncd lost during the move: " + link_.why());
    const std::optional<shm::JobStatus> job = link_.job();
    if (job && job->jobs_ended != before->jobs_ended && !job->job_active) {
      if (job->last_fault != 0) return fail(std::string("the move ended in a fault: ") + job->message);
      return {};
    }
    if (std::chrono::steady_clock::now() > deadline) {
      link_.send(shm::CommandType::Stop);
      return fail("the move did not end in time; stopped");
    }
    std::this_thread::sleep_for(kPoll);
  }
}

}  // namespace lcnc::hmi
