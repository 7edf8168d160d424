#pragma once
/// What the shake-table workflows need from the program that runs them: where their lines go,
/// how a campaign reports progress, how a scan is imported. The commands (app) print; tests
/// collect the lines or pass nothing.
#include <functional>
#include <string>

#include "rigid/campaign/options.hpp"
#include "rigid/scan/import.hpp"

namespace rigid::shaketable {

struct Callbacks {
  /// One line for the user (no newline); default: dropped.
  std::function<void(const std::string&)> say;
  /// Called on each designed campaign's options before it runs (e.g. to attach progress), with
  /// what the campaign is for ("shaketable: stage 3 (extend K_N down to 2.5e5)"): its progress
  /// lines say it.
  std::function<void(campaign::CampaignOptions&, const std::string& what)> on_campaign;
  /// Imports a scan (default: scan::import_scan, silently).
  std::function<void(const scan::ImportOptions&)> import_scan;

  void tell(const std::string& line) const {
    if (say) say(line);
  }
};

}  // namespace rigid::shaketable
