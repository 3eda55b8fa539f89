#pragma once
// SIGINT and SIGTERM ask the run to stop after the frame in progress: finished cells are on disk,
// the cell in progress is dropped, and the same command resumes.
namespace cdb {

void installInterruptHandlers();
[[nodiscard]] bool interruptRequested();
[[nodiscard]] int interruptSignal();  // the signal received, 0 if none

}  // namespace cdb
