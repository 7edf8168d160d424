// `rigid shaketable transfer`: the flags of the transfer workflow (rigid::shaketable::
// transfer_calibration) and what it prints.
#include <cstdio>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "number_checks.hpp"
#include "output_options.hpp"
#include "rigid/core/error.hpp"
#include "rigid/shaketable/calibration_document.hpp"
#include "rigid/shaketable/transfer.hpp"
#include "shaketable.hpp"

namespace rigid::app {
namespace {

struct TransferFlags {
  rigid::shaketable::TransferSettings settings;
  std::string heading;
};

void print_summary(const rigid::shaketable::TransferSummary& s) {
  std::printf(
      "\ntransferred: %zu members merged into %zu (%zu physics), each over %zu headings; heaviest %s (weight %.3f)\n",
      s.source_members, s.members, s.physics, s.rotations, s.heaviest.c_str(), s.heaviest_weight);
  std::printf("wrote %s, %s (%.0f s)\n", s.scene.c_str(), s.json.c_str(), s.wall_s);
}

}  // namespace

void add_shaketable_transfer(CLI::App& parent) {
  auto f = std::make_shared<TransferFlags>();
  rigid::shaketable::TransferSettings& o = f->settings;
  CLI::App* cmd = parent.add_subcommand(
      "transfer",
      "Carry a calibration's physics ensemble (base models, contact laws, impact laws, friction, weights) to another "
      "scanned rock, settled under each law, its heading on a table unknown unless given; reads no outcome of the new "
      "rock. Writes OUT.toml and OUT.calibration.json (for predict, fragility and campaigns) and the work folder "
      "OUT.transfer/ (run again to resume)");
  cmd->add_option("calibration", o.calibration, "NAME.calibration.json of rigid shaketable calibrate")->required();
  cmd->add_option("scan", o.scan, "The new rock's scan (OBJ, PLY, STL), as for rigid model import")->required();
  add_output_prefix(*cmd, o.out,
                    "NAME.toml (the heaviest member's scene), NAME.calibration.json, the work folder "
                    "NAME.transfer/")
      ->required();
  shaketable::add_scan_import_options(*cmd, o.scan_import);
  cmd->add_option("--headings", o.headings,
                  "Headings on a full ring: the new rock's heading on the table, unknown, is each of them alike")
      ->capture_default_str();
  cmd->add_option("--heading", f->heading,
                  "The new rock's heading on the table when known (deg, in the scan's frame, as calibrate reports it: "
                  "the scene is turned to it), or weakest: its weakest rocking direction, either way along the axis "
                  "(a lab that tests a rock's most fragile direction)");
  cmd->add_option("--heading-spread", o.heading_spread_deg,
                  "With --heading: the ring's headings within this angle of it (of its axis, for weakest) count alike "
                  "(deg)")
      ->capture_default_str();
  cmd->add_flag("--restart", o.restart,
                "Start over: remove the work folder OUT.transfer/ of an earlier transfer into the same OUT (a rerun "
                "otherwise resumes it, and is refused when the calibration, the scan or the import flags changed)");
  cmd->callback([f] {
    if (f->heading == "weakest") {
      f->settings.heading_weakest = true;
    } else if (!f->heading.empty()) {
      const std::optional<double> deg = whole_number(f->heading);
      if (!deg) throw InputError("", 0, "--heading: '" + f->heading + "' is neither an angle (deg) nor weakest");
      f->settings.heading_deg = *deg;
    }
    f->settings.command_line = rigid::shaketable::command_line_text(campaign_argc(), campaign_argv());
    // rank 0 works (no campaign: imports and settling take seconds); other ranks wait for it
    std::optional<rigid::shaketable::TransferSummary> summary;
    shaketable::run_designed_campaigns(
        [&](const campaign::CampaignResult*) -> std::optional<campaign::CampaignOptions> {
          summary = rigid::shaketable::transfer_calibration(f->settings, shaketable::command_callbacks("none"));
          return std::nullopt;
        },
        [&](const campaign::CampaignResult&) { print_summary(*summary); });
  });
}

}  // namespace rigid::app
