#include "cli.h"
#include "interrupt.h"

int main(int argc, char** argv) {
    gbl::installInterruptHandling();  // before any thread (lavapipe's, ours) exists
    return gbl::runCli(argc, argv);
}
