#include "AtomicFile.h"

#include "Errors.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include <unistd.h>

namespace snaresim::render
{
namespace
{

// Creates the file only if it does not exist ("x": O_EXCL). Returns errno, or 0.
int createExclusive(const std::filesystem::path& path)
{
    errno = 0;
    std::FILE* file = std::fopen(path.c_str(), "wbx");
    if (file == nullptr)
        return errno != 0 ? errno : EIO;
    if (std::fclose(file) != 0)
        return errno != 0 ? errno : EIO;
    return 0;
}

} // namespace

AtomicFile::AtomicFile(std::filesystem::path target) : targetPath(std::move(target))
{
    std::error_code ec;

    if (! targetPath.has_filename())
        throw UserError("cannot write " + displayName() + ": not a file name");
    if (std::filesystem::is_directory(targetPath, ec))
        throw UserError("cannot write " + displayName() + ": it is a directory");

    static std::atomic<unsigned> counter { 0 };
    std::string stem(1, '.');
    stem += targetPath.filename().string();
    stem += ".tmp-";
    stem += std::to_string((long) ::getpid());
    stem += '-';

    for (int attempt = 0; attempt < 100; ++attempt)
    {
        auto candidate = targetPath;
        candidate.replace_filename(stem + std::to_string(counter++));

        const int error = createExclusive(candidate);
        if (error == 0)
        {
            tempPath = std::move(candidate);
            return;
        }
        if (error != EEXIST)
        {
            auto reason = std::string(std::strerror(error));
            const auto directory = targetPath.parent_path();
            if (error == ENOENT && ! directory.empty() && ! std::filesystem::exists(directory, ec))
                reason = "directory " + inQuotes(directory.string()) + " does not exist";
            throw UserError("cannot write " + displayName() + ": " + reason);
        }
    }
    throw UserError("cannot write " + displayName() + ": no free temporary file name");
}

AtomicFile::~AtomicFile()
{
    if (! isCommitted && ! tempPath.empty())
    {
        std::error_code ec;
        std::filesystem::remove(tempPath, ec);
    }
}

std::string AtomicFile::displayName() const { return inQuotes(targetPath.string()); }

void AtomicFile::commit()
{
    std::error_code ec;
    std::filesystem::rename(tempPath, targetPath, ec);
    if (ec)
        throw UserError("cannot write " + displayName() + ": " + ec.message());
    isCommitted = true;
}

void AtomicFile::discardCommitted() noexcept
{
    if (isCommitted)
    {
        std::error_code ec;
        std::filesystem::remove(targetPath, ec);
    }
}

} // namespace snaresim::render
