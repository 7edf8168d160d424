#pragma once
/// SIGTERM, SIGINT and SIGUSR1 ask a campaign to stop: no new tasks, a final checkpoint, exit 75.

namespace rigid::campaign {

void install_stop_signal_handlers();
/// The signal received, or 0.
int stop_signal();

}  // namespace rigid::campaign
