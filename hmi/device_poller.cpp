#include "hmi/device_poller.h"

#include "drivers/modbus/register_map.h"

namespace lcnc::hmi {

Result<std::unique_ptr<DevicePoller>> DevicePoller::start(const std::string& device,
                                                          const drivers::Endpoint& at,
                                                          std::vector<std::string> history,
                                                          std::chrono::milliseconds period,
                                                          double history_s) {
  Result<drivers::DeviceMap> map = drivers::shipped_device(device);
  if (!map) return map.error();
  for (const std::string& h : history)
    if (Result<const drivers::RegisterDef*> r = map->lookup(h); !r) return r.error();
  drivers::MasterConfig c;
  c.endpoint = at;
  auto m = std::make_unique<drivers::ModbusMaster>(*map, c);
  if (Status s = m->start(); !s) return s.error();
  std::unique_ptr<DevicePoller> p(new DevicePoller(std::move(m), std::move(history), period, history_s));
  p->thread_ = std::thread([raw = p.get()] { raw->run(); });
  return p;
}

DevicePoller::DevicePoller(std::unique_ptr<drivers::ModbusMaster> m, std::vector<std::string> history,
                           std::chrono::milliseconds period, double history_s)
    : master_(std::move(m)), history_names_(std::move(history)), period_(period), history_s_(history_s) {
  for (drivers::Table t :
       {drivers::Table::Coil, drivers::Table::Discrete, drivers::Table::Holding, drivers::Table::Input}) {
    std::vector<std::string> names;
    for (const drivers::RegisterDef& r : master_->map().registers)
      if (r.table == t) names.push_back(r.name);
    if (!names.empty()) blocks_.push_back(std::move(names));
  }
}

DevicePoller::~DevicePoller() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
  master_->stop();
}

void DevicePoller::run() noexcept {
  while (running_.load()) {
    const auto next = std::chrono::steady_clock::now() + period_;
    std::map<std::string, double> got;
    std::string error;
    for (const std::vector<std::string>& block : blocks_) {
      Result<std::vector<double>> r = master_->read_block(block).get();
      if (!r) {
        error = r.error().message;
        break;
      }
      for (std::size_t i = 0; i < block.size(); ++i) got[block[i]] = (*r)[i];
    }
    {
      std::lock_guard lock(mutex_);
      for (const auto& [k, v] : got) snap_.values[k] = v;
      snap_.linked = error.empty();
      snap_.error = error;
      snap_.counters = master_->counters();
      ++snap_.polls;
      if (error.empty() && !history_names_.empty()) {
        HistorySample h;
        h.t_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
        for (const std::string& n : history_names_) h.values.push_back(got[n]);
        history_.push_back(std::move(h));
        while (!history_.empty() && history_.back().t_s - history_.front().t_s > history_s_)
          history_.pop_front();
      }
    }
    while (running_.load() && std::chrono::steady_clock::now() < next)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

PollSnapshot DevicePoller::snapshot() const {
  std::lock_guard lock(mutex_);
  return snap_;
}

std::vector<HistorySample> DevicePoller::history() const {
  std::lock_guard lock(mutex_);
  return {history_.begin(), history_.end()};
}

void DevicePoller::write(const std::string& name, double value) {
  {
    std::lock_guard lock(mutex_);
    snap_.last_write.clear();
  }
  master_->write_async(name, value, [this, name](const Status& s) {
    std::lock_guard lock(mutex_);
    snap_.last_write = s ? std::string() : name + ": " + s.error().message;
  });
}

void DevicePoller::write_block(const std::vector<std::pair<std::string, double>>& values) {
  {
    std::lock_guard lock(mutex_);
    snap_.last_write.clear();
  }
  master_->write_block_async(values, [this](const Status& s) {
    std::lock_guard lock(mutex_);
    snap_.last_write = s ? std::string() : s.error().message;
  });
}

}  // namespace lcnc::hmi
