#pragma once
// `rigid model import`, also run by `rigid shaketable calibrate` for each model of the scanned
// base it compares: the import (scan::import_scan) and its report on stdout and stderr.
#include "rigid/scan/import.hpp"

namespace rigid::app {

/// Imports a scan and prints what the import did: warnings on stderr, the summary on stdout.
/// Throws InputError for bad options or a bad scan.
void import_and_report(const scan::ImportOptions& o);

}  // namespace rigid::app
