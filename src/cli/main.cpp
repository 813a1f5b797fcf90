#include "cli.h"
#include "host_profile.h"
#include "interrupt.h"

int main(int argc, char** argv) {
    gbl::installInterruptHandling();  // before any thread (lavapipe's, ours) exists
    gbl::HostScope scope("main: the whole command");
    return gbl::runCli(argc, argv);
}
