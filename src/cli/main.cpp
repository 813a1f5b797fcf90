#include "cli.h"

int main(int argc, char** argv) { return gbl::runCli(argc, argv); }
