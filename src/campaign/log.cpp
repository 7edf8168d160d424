#include "rigid/campaign/log.hpp"

#include <spdlog/sinks/stdout_sinks.h>

#include <memory>

namespace rigid::campaign {

spdlog::logger& campaign_log() {
  static const std::shared_ptr<spdlog::logger> log = [] {
    auto l = std::make_shared<spdlog::logger>("rigid campaign", std::make_shared<spdlog::sinks::stderr_sink_mt>());
    l->set_pattern("%Y-%m-%d %H:%M:%S rigid campaign: %v");
    l->flush_on(spdlog::level::trace);  // a log read while the campaign runs, or after a kill
    return l;
  }();
  return *log;
}

void log_warning(const std::string& message) { campaign_log().warn("warning: {}", message); }

}  // namespace rigid::campaign
