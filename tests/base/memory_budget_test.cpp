// The memory budget (base/memory_budget.h): its formula, its override, and the one line a
// refusal prints.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "error.h"
#include "file_io.h"
#include "memory_budget.h"

namespace gbl {
namespace {

constexpr uint64_t kGiB = uint64_t(1) << 30;

TEST(MemoryBudget, ThreeQuartersOfTheMachineUnlessSet) {
    const MemoryBudget b = makeMemoryBudget(nullptr, 24 * kGiB);
    EXPECT_EQ(b.bytes, 18 * kGiB);
    EXPECT_NE(b.source.find("3/4 of the machine's 24 GiB"), std::string::npos) << b.source;
    EXPECT_EQ(makeMemoryBudget("", 24 * kGiB).bytes, 18 * kGiB);
    EXPECT_EQ(makeMemoryBudget("8G", 24 * kGiB).bytes, 8 * kGiB);
    EXPECT_EQ(makeMemoryBudget("512M", 24 * kGiB).bytes, 512u << 20);
    // Never more than the machine has.
    const MemoryBudget capped = makeMemoryBudget("64G", 24 * kGiB);
    EXPECT_EQ(capped.bytes, 24 * kGiB);
    EXPECT_NE(capped.source.find("capped"), std::string::npos) << capped.source;
    for (const char* bad : {"lots", "0", "1.5G", "8X", "-1G", "99999999999999999999", "20000000T"}) {
        SCOPED_TRACE(bad);
        try {
            makeMemoryBudget(bad, 24 * kGiB);
            FAIL() << "expected a UserError";
        } catch (const UserError& e) {
            EXPECT_NE(std::string(e.what()).find("GBL_MEMORY_BUDGET"), std::string::npos) << e.what();
        }
    }
}

TEST(MemoryBudget, ParsesBinaryUnits) {
    EXPECT_EQ(parseByteCount("1073741824"), kGiB);
    EXPECT_EQ(parseByteCount("1G"), kGiB);
    EXPECT_EQ(parseByteCount("1GiB"), kGiB);
    EXPECT_EQ(parseByteCount("1gb"), kGiB);
    EXPECT_EQ(parseByteCount("2K"), 2048u);
    EXPECT_EQ(parseByteCount("3T"), uint64_t(3) << 40);
    EXPECT_EQ(parseByteCount(""), 0u);
    EXPECT_EQ(parseByteCount("G"), 0u);
}

TEST(MemoryBudget, BytesAreWrittenForPeople) {
    EXPECT_EQ(formatBytes(17), "17 B");
    EXPECT_EQ(formatBytes(1536), "1.5 KiB");
    EXPECT_EQ(formatBytes(820.0 * (1 << 20)), "820 MiB");
    EXPECT_EQ(formatBytes(29.5 * double(kGiB)), "30 GiB");
    EXPECT_EQ(formatBytes(1e300).find("EiB") != std::string::npos, true);  // a hostile estimate stays a size
}

// The process's own budget comes from GBL_MEMORY_BUDGET, read once: set here before first use.
TEST(MemoryBudget, ARefusalIsOneLineNamingWhatTheBudgetAndTheFix) {
    ASSERT_EQ(::setenv("GBL_MEMORY_BUDGET", "1G", 1), 0);
    EXPECT_LE(memoryBudget().bytes, kGiB);
    EXPECT_NO_THROW(requireMemory(0.5 * double(memoryBudget().bytes), "small", "fix"));
    try {
        requireMemory(1e30, "a.png (99999x99999)", "give a smaller image");
        FAIL() << "expected a UserError";
    } catch (const UserError& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.rfind("a.png (99999x99999): needs about ", 0), 0u) << m;
        EXPECT_NE(m.find("GBL_MEMORY_BUDGET=1G"), std::string::npos) << m;
        EXPECT_NE(m.find("; give a smaller image"), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
    // A file's size is held to the budget before it is read: a sparse 2 GiB file (no disk used).
    const std::filesystem::path big = std::filesystem::temp_directory_path() /
                                      ("gbl_memory_budget_test_" + std::to_string(::getpid()) + ".bin");
    { std::ofstream(big.string()) << ""; }
    std::filesystem::resize_file(big, 2 * kGiB);
    try {
        readBinaryFile(big);
        ADD_FAILURE() << "expected a UserError";
    } catch (const UserError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find(big.filename().string() + " (a file of 2.0 GiB): needs about 2.0 GiB"), std::string::npos) << m;
        EXPECT_NE(m.find("GBL_MEMORY_BUDGET=1G"), std::string::npos) << m;
    }
    std::filesystem::remove(big);
}

}  // namespace
}  // namespace gbl
