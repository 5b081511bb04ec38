// The LaserCNC HAL component: LaserCNC's RT kernel, run by a LinuxCNC HAL
// thread, driving HAL pins. Loaded into rtapi_app (LinuxCNC "uspace") with
//
//     loadrt lasercnc segment=/lasercnc
//     addf lasercnc.update servo-thread
//
// beside a `lasercncd --hal` that owns the segments /lasercnc (status,
// commands, e-stop word) and /lasercnc.hal (the kernel's port, position
// buffer, trace and log: rt/hal_block.h). The daemon plans and streams as
// it always does; this component is the RT side. Each run of
// lasercnc.update is one kernel period: commands and inputs, one entry of
// the position buffer, limits, e-stop. Where the pulses come from: the
// kernel's micro-steps are summed per axis into counts, and pos-cmd =
// counts / steps_per_unit (machine units), which a HAL stepgen (software or
// Mesa hm2) in position mode or a servo loop follows. So in HAL the step
// generator is HAL's; the kernel's own DDA only counts.
//
// Pins (A = x, y, z, a, b, c for the axes the machine has):
//   lasercnc.A.pos-cmd    out float  commanded position, machine units, in the
//                                    motor's frame: counts / steps_per_unit
//                                    from power-on (homing moves LaserCNC's
//                                    coordinate, never this pin)
//   lasercnc.A.counts     out s32    the steps commanded since power-on: a
//                                    stepgen following pos-cmd ends on them
//   lasercnc.A.pos-fb     in  float  measured position (stepgen position-fb, encoder)
//   lasercnc.A.home-sw    in  bit    home switch
//   lasercnc.A.limit-min  in  bit    hard limit, low end
//   lasercnc.A.limit-max  in  bit    hard limit, high end
//   lasercnc.laser-power  out float  0 … 1 of rated power (a PWM generator's value)
//   lasercnc.laser-on     out bit    the beam is commanded on
//   lasercnc.enable       out bit    drives enabled (false in e-stop)
//   lasercnc.estop-in     in  bit    an external e-stop chain is open
//   lasercnc.amp-fault    in  bit    a drive reports a fault
//   lasercnc.on-path      out bit    a job runs (running, held, stopping)
//   lasercnc.segment      out s32    the program segment being executed
//   lasercnc.line         out s32    its program line
//   lasercnc.digital-out-NN out bit  the program's digital output NN (00 … 07:
//                                    M62/M63 with the next move, M64/M65 where
//                                    they stand); off when no job is on the path
//   lasercnc.analog-out-NN  out float the program's analog output NN (00 … 03:
//                                    M67 with the next move, M68); 0 off the path
//   lasercnc.digital-in-NN in bit    the program's digital input NN (00 … 07):
//                                    M66 P NN L1…L4 Q… waits for it
//   lasercnc.mist         out bit    assist gas, low pressure (M7)
//   lasercnc.flood        out bit    assist gas, high pressure (M8)
// Following error: |pos-cmd − pos-fb| beyond the axis's
// `following_error` (machine TOML) stops the machine and names the axis.
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <new>
#include <string>

#include "hal.h"
#include "rtapi.h"
#include "rtapi_app.h"

#include "machine/machine_config.h"
#include "machine/pulse_sink.h"
#include "rt/hal_block.h"
#include "rt/rt_kernel.h"
#include "rt/shm_interface.h"

MODULE_AUTHOR("LaserCNC");
MODULE_DESCRIPTION("LaserCNC RT kernel as a HAL component");
MODULE_LICENSE("GPL");

static char* segment = const_cast<char*>("/lasercnc");
RTAPI_MP_STRING(segment, "name of lasercncd's shared-memory segment");

namespace {

using namespace lcnc;

struct AxisPins {
  hal_float_t* pos_cmd;
  hal_s32_t* counts;
  hal_float_t* pos_fb;
  hal_bit_t* home_sw;
  hal_bit_t* limit_min;
  hal_bit_t* limit_max;
};

// Pin storage: in HAL's shared memory (hal_malloc), as HAL requires.
struct Pins {
  AxisPins axis[kAxisCount];
  hal_float_t* laser_power;
  hal_bit_t* laser_on;
  hal_bit_t* enable;
  hal_bit_t* estop_in;
  hal_bit_t* amp_fault;
  hal_bit_t* on_path;
  hal_s32_t* segment;
  hal_s32_t* line;
  hal_bit_t* digital_out[kDigitalOutputs];
  hal_float_t* analog_out[kAnalogOutputs];
  hal_bit_t* mist;
  hal_bit_t* flood;
  hal_bit_t* digital_in[kDigitalInputs];
  hal_float_t* adaptive_feed;
  hal_bit_t* feed_hold;
};

// The kernel's pulse sink: counts and pins.
class HalSink final : public PulseSink {
 public:
  HalSink(const MachineConfig& m, Pins* pins, const std::array<std::int64_t, kAxisCount>& start)
      : pins_(pins), counts_(start) {
    for (int i = 0; i < kAxisCount; ++i) {
      present_[i] = m.axes[i].present;
      units_per_step_[i] = present_[i] ? 1.0 / m.axes[i].steps_per_unit : 0.0;
      ferror_[i] = m.axes[i].following_error;
      if (present_[i]) show(i);
    }
  }

  void send(const PulseFrame& frame) noexcept override {
    for (int i = 0; i < kAxisCount; ++i) {
      if (!present_[i]) continue;
      const AxisPulses& p = frame.axes[i];
      counts_[i] += p.negative ? -static_cast<std::int64_t>(p.count) : static_cast<std::int64_t>(p.count);
      show(i);
    }
    *pins_->laser_power = frame.power_pct / 100.0f;
    *pins_->laser_on = frame.power_pct > 0.0f;
    for (int n = 0; n < kDigitalOutputs; ++n) *pins_->digital_out[n] = (frame.outputs >> n) & 1u;
    for (int n = 0; n < kAnalogOutputs; ++n)
      *pins_->analog_out[n] = frame.analog[static_cast<std::size_t>(n)];
    *pins_->mist = (frame.outputs & kOutputMist) != 0;
    *pins_->flood = (frame.outputs & kOutputFlood) != 0;
  }

  MachineInputs read_inputs() noexcept override {
    MachineInputs in;
    for (int i = 0; i < kAxisCount; ++i) {
      if (!present_[i]) continue;
      const AxisPins& a = pins_->axis[i];
      in.home[i] = *a.home_sw;
      in.limit_min[i] = *a.limit_min;
      in.limit_max[i] = *a.limit_max;
      if (in.following_error_axis < 0 && ferror_[i] > 0.0 && std::abs(*a.pos_cmd - *a.pos_fb) > ferror_[i])
        in.following_error_axis = i;
    }
    in.estop = *pins_->estop_in;
    in.amp_fault = *pins_->amp_fault;
    for (int n = 0; n < kDigitalInputs; ++n)
      if (*pins_->digital_in[n]) in.digital_in = static_cast<std::uint8_t>(in.digital_in | (1u << n));
    in.adaptive_feed = static_cast<float>(*pins_->adaptive_feed);
    in.feed_hold = *pins_->feed_hold;
    return in;
  }

 private:
  void show(int i) noexcept {
    *pins_->axis[i].pos_cmd = static_cast<double>(counts_[i]) * units_per_step_[i];
    *pins_->axis[i].counts = static_cast<std::int32_t>(counts_[i]);
  }

  Pins* pins_;
  std::array<std::int64_t, kAxisCount> counts_;
  std::array<bool, kAxisCount> present_{};
  std::array<double, kAxisCount> units_per_step_{};
  std::array<double, kAxisCount> ferror_{};
};

// A mapped segment, unmapped on destruction.
struct Mapping {
  void* at = MAP_FAILED;
  std::size_t size = 0;
  ~Mapping() {
    if (at != MAP_FAILED) munmap(at, size);
  }
};

bool map_segment(const std::string& name, std::size_t size, Mapping& out) {
  const int fd = shm_open(name.c_str(), O_RDWR, 0);
  if (fd < 0) return false;
  struct stat st {};
  if (fstat(fd, &st) != 0 || static_cast<std::size_t>(st.st_size) < size) {
    close(fd);
    return false;
  }
  out.at = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  out.size = size;
  close(fd);
  return out.at != MAP_FAILED;
}

struct Component {
  Mapping main, hal;
  shm::ShmBlock* block = nullptr;
  shm::HalBlock* hb = nullptr;
  MachineConfig machine;
  std::unique_ptr<HalSink> sink;
  std::unique_ptr<rt::RtKernel> kernel;
  Pins* pins = nullptr;
  bool period_checked = false;
  bool stopped = false;
};

int comp_id = -1;
Component* component = nullptr;

std::int64_t now_ns() noexcept {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

// One kernel period per run of the HAL thread.
void update(void* arg, long period_ns) {
  Component* c = static_cast<Component*>(arg);
  if (c->stopped) return;
  if (!c->period_checked) {
    c->period_checked = true;
    // the plan's period must be the thread's: say so once and e-stop
    if (period_ns != static_cast<long>(c->machine.period_ns)) {
      rtapi_print_msg(RTAPI_MSG_ERR,
                      "lasercnc: the HAL thread's period is %ld ns, the machine's period_ns %u: e-stop\n",
                      period_ns, c->machine.period_ns);
      c->block->estop.requests.fetch_add(1, std::memory_order_acq_rel);
    }
  }
  *c->pins->enable = c->kernel->state() != rt::MachineState::EStop;
  if (!c->kernel->period(now_ns(), -1)) {
    c->kernel->end_periods();
    c->stopped = true;
  }
  const rt::MachineState st = c->kernel->state();
  *c->pins->on_path =
      st == rt::MachineState::Running || st == rt::MachineState::FeedHold || st == rt::MachineState::Stopping;
  *c->pins->segment = static_cast<std::int32_t>(c->hb->port.segment.load(std::memory_order_relaxed));
  *c->pins->line = static_cast<std::int32_t>(c->hb->port.line.load(std::memory_order_relaxed));
}

template <class T>
int pin_new(hal_pin_dir_t dir, T** p, const char* fmt, const char* a = nullptr);

template <>
int pin_new(hal_pin_dir_t dir, hal_float_t** p, const char* fmt, const char* a) {
  return a ? hal_pin_float_newf(dir, p, comp_id, fmt, a) : hal_pin_float_newf(dir, p, comp_id, "%s", fmt);
}
template <>
int pin_new(hal_pin_dir_t dir, hal_s32_t** p, const char* fmt, const char* a) {
  return a ? hal_pin_s32_newf(dir, p, comp_id, fmt, a) : hal_pin_s32_newf(dir, p, comp_id, "%s", fmt);
}
template <>
int pin_new(hal_pin_dir_t dir, hal_bit_t** p, const char* fmt, const char* a) {
  return a ? hal_pin_bit_newf(dir, p, comp_id, fmt, a) : hal_pin_bit_newf(dir, p, comp_id, "%s", fmt);
}

int setup(Component& c) {
  const std::string name = segment;
  if (!map_segment(name, sizeof(shm::ShmBlock), c.main)) {
    rtapi_print_msg(RTAPI_MSG_ERR, "lasercnc: no segment %s: start lasercncd --hal first\n", name.c_str());
    return -ENOENT;
  }
  if (!map_segment(name + ".hal", sizeof(shm::HalBlock), c.hal)) {
    rtapi_print_msg(RTAPI_MSG_ERR, "lasercnc: no segment %s.hal: lasercncd runs without --hal\n",
                    name.c_str());
    return -ENOENT;
  }
  c.block = static_cast<shm::ShmBlock*>(c.main.at);
  c.hb = static_cast<shm::HalBlock*>(c.hal.at);
  const shm::HalHeader& h = c.hb->header;
  if (h.magic != shm::kHalMagic || h.version != shm::kHalVersion || h.size != sizeof(shm::HalBlock)) {
    rtapi_print_msg(RTAPI_MSG_ERR, "lasercnc: %s.hal is not this version's (rebuild both)\n", name.c_str());
    return -EINVAL;
  }
  Result<MachineConfig> m =
      load_machine_config(std::string(h.machine_path, strnlen(h.machine_path, sizeof h.machine_path)));
  if (!m) {
    rtapi_print_msg(RTAPI_MSG_ERR, "lasercnc: %s\n", m.error().to_string().c_str());
    return -EINVAL;
  }
  c.machine = std::move(m).value();
  c.pins = static_cast<Pins*>(hal_malloc(sizeof(Pins)));
  if (c.pins == nullptr) return -ENOMEM;
  for (int i = 0; i < kAxisCount; ++i) {
    if (!c.machine.axes[i].present) continue;
    const char ax[2] = {static_cast<char>(kAxisLetters[i] - 'A' + 'a'), 0};
    AxisPins& p = c.pins->axis[i];
    int r = 0;
    r |= pin_new(HAL_OUT, &p.pos_cmd, "lasercnc.%s.pos-cmd", ax);
    r |= pin_new(HAL_OUT, &p.counts, "lasercnc.%s.counts", ax);
    r |= pin_new(HAL_IN, &p.pos_fb, "lasercnc.%s.pos-fb", ax);
    r |= pin_new(HAL_IN, &p.home_sw, "lasercnc.%s.home-sw", ax);
    r |= pin_new(HAL_IN, &p.limit_min, "lasercnc.%s.limit-min", ax);
    r |= pin_new(HAL_IN, &p.limit_max, "lasercnc.%s.limit-max", ax);
    if (r != 0) return -EINVAL;
  }
  int r = 0;
  r |= pin_new(HAL_OUT, &c.pins->laser_power, "lasercnc.laser-power");
  r |= pin_new(HAL_OUT, &c.pins->laser_on, "lasercnc.laser-on");
  r |= pin_new(HAL_OUT, &c.pins->enable, "lasercnc.enable");
  r |= pin_new(HAL_IN, &c.pins->estop_in, "lasercnc.estop-in");
  r |= pin_new(HAL_IN, &c.pins->amp_fault, "lasercnc.amp-fault");
  r |= pin_new(HAL_OUT, &c.pins->on_path, "lasercnc.on-path");
  r |= pin_new(HAL_OUT, &c.pins->segment, "lasercnc.segment");
  r |= pin_new(HAL_OUT, &c.pins->line, "lasercnc.line");
  for (int n = 0; n < kDigitalOutputs; ++n) {
    char name[40];
    std::snprintf(name, sizeof name, "lasercnc.digital-out-%02d", n);
    r |= pin_new(HAL_OUT, &c.pins->digital_out[n], name);
  }
  for (int n = 0; n < kAnalogOutputs; ++n) {
    char name[40];
    std::snprintf(name, sizeof name, "lasercnc.analog-out-%02d", n);
    r |= pin_new(HAL_OUT, &c.pins->analog_out[n], name);
  }
  for (int n = 0; n < kDigitalInputs; ++n) {
    char name[40];
    std::snprintf(name, sizeof name, "lasercnc.digital-in-%02d", n);
    r |= pin_new(HAL_IN, &c.pins->digital_in[n], name);
  }
  r |= pin_new(HAL_IN, &c.pins->adaptive_feed, "lasercnc.adaptive-feed");
  r |= pin_new(HAL_IN, &c.pins->feed_hold, "lasercnc.feed-hold");
  r |= pin_new(HAL_OUT, &c.pins->mist, "lasercnc.mist");
  r |= pin_new(HAL_OUT, &c.pins->flood, "lasercnc.flood");
  if (r != 0) return -EINVAL;
  *c.pins->adaptive_feed = 1.0;  // unconnected: full feed (as LinuxCNC's motion.adaptive-feed)
  c.sink = std::make_unique<HalSink>(c.machine, c.pins, h.start_steps);
  c.kernel = std::make_unique<rt::RtKernel>(c.machine, c.hb->buffer, *c.sink, &c.hb->trace, h.start_steps,
                                            &c.hb->port);
  c.kernel->set_log(&c.hb->log);
  c.kernel->set_status(&c.block->status);
  c.kernel->set_estop_word(&c.block->estop.requests);
  rt::RtOptions opt;
  opt.exit_at_end = false;
  opt.start_running = false;
  // real drives come up unhomed, unless the machine has no switches
  opt.start_homed = c.machine.allow_unhomed;
  c.kernel->begin(opt);
  if (hal_export_funct("lasercnc.update", update, &c, 1, 0, comp_id) != 0) return -EINVAL;
  c.hb->header.attached.store(getpid(), std::memory_order_release);
  return 0;
}

}  // namespace

extern "C" int rtapi_app_main(void) {
  comp_id = hal_init("lasercnc");
  if (comp_id < 0) return comp_id;
  component = new (std::nothrow) Component;
  if (component == nullptr) {
    hal_exit(comp_id);
    return -ENOMEM;
  }
  if (const int r = setup(*component); r != 0) {
    delete component;
    component = nullptr;
    hal_exit(comp_id);
    return r;
  }
  hal_ready(comp_id);
  return 0;
}

extern "C" void rtapi_app_exit(void) {
  if (component != nullptr) {
    component->hb->header.attached.store(0, std::memory_order_release);
    delete component;
    component = nullptr;
  }
  hal_exit(comp_id);
}
