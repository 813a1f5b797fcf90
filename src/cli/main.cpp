#include <csignal>

#include "cli.h"
#include "host_profile.h"
#include "interrupt.h"
#include "standard_output.h"

int main(int argc, char** argv) {
    // A reader that closes its end of a pipe makes a write to stdout fail (EPIPE), which
    // closeStandardOutput reports in one line and exit status 1, rather than a death by SIGPIPE.
    std::signal(SIGPIPE, SIG_IGN);
    gbl::installInterruptHandling();  // before any thread (lavapipe's, ours) exists
    gbl::bufferStandardOutput();      // before any output
    int status = 0;
    {
        gbl::HostScope scope("main: the whole command");
        status = gbl::runCli(argc, argv);
    }
    // Every command's text on stdout (tables, layouts, shaders, JSON) is checked here, once.
    return gbl::closeStandardOutput(status);
}
