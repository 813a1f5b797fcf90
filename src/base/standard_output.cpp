#include "standard_output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#include <unistd.h>

namespace gbl {

void bufferStandardOutput() {
    if (::isatty(STDOUT_FILENO)) return;
    static char buffer[1 << 20];
    std::setvbuf(stdout, buffer, _IOFBF, sizeof buffer);
}

int closeStandardOutput(int status) {
    // std::cout writes through stdout (synchronised with stdio): its flush is stdout's, and the
    // first failure's errno is the cause.
    errno = 0;
    std::cout.flush();
    const bool streamFailed = std::cout.fail();
    int error = streamFailed || std::ferror(stdout) ? errno : 0;
    errno = 0;
    const bool flushFailed = std::fflush(stdout) != 0;
    if (flushFailed && !error) error = errno;
    const bool earlierFailed = std::ferror(stdout) != 0;  // a write while the command ran
    errno = 0;
    const bool closeFailed = std::fclose(stdout) != 0;
    if (closeFailed && !error) error = errno;
    if (!streamFailed && !flushFailed && !earlierFailed && !closeFailed) return status;
    // EBADF: stdout was closed before the command started (`>&-`); no error code: an earlier write failed.
    const std::string cause = error == EBADF ? std::string("it is closed")
                              : error        ? std::string(std::strerror(error))
                                             : std::string("a write failed: a full disk or device, or a closed pipe");
    std::fprintf(stderr, "gbufferlab: error: standard output: the output is incomplete (%s); write it to a file "
                         "with space left, or to a pipe that stays open\n",
                 cause.c_str());
    return status != 0 ? status : 1;
}

}  // namespace gbl
