#pragma once
/// The status lines of a campaign on stderr, each stamped with the date and time: a campaign runs
/// for hours under a batch system, where its stderr is read as a log. spdlog (Debian
/// libspdlog-dev) stamps and writes each line whole, from any thread. Error lines keep the plain
/// one-line `rigid: error: ...` format of every command.
#include <spdlog/spdlog.h>

#include <utility>

namespace rigid::campaign {

/// The campaign's logger: "2026-11-24 06:20:01 rigid campaign: ..." on stderr.
spdlog::logger& campaign_log();

/// log_status("{} tasks done", n): a status line.
template <typename... Args>
void log_status(spdlog::format_string_t<Args...> format, Args&&... args) {
  campaign_log().info(format, std::forward<Args>(args)...);
}

/// A line "... rigid campaign: warning: MESSAGE".
void log_warning(const std::string& message);

}  // namespace rigid::campaign
