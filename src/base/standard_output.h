#pragma once
// Standard output is a file the user gave (`> report.txt`, `| less`, `> /dev/full`): a write to
// it that fails is an error of the command, never a silent exit 0 with half the text.
namespace gbl {

// Called once, first thing in main(): stdout not a terminal gets a buffer of 1 MiB, so that the
// text of a command (a layout's shader, a table, JSON) is written by closeStandardOutput's flush,
// whose failure names its cause (errno); a write that failed earlier is still caught, with a
// general cause. A terminal stays line-buffered.
void bufferStandardOutput();

// Called once, when the command has returned: flushes std::cout and stdout and closes stdout (a
// file system may report a failed write only then). When any write to stdout failed, prints one
// line naming the cause to stderr and returns 1; otherwise, or when `status` is already non-zero,
// returns `status`.
int closeStandardOutput(int status);

}  // namespace gbl
