#pragma once
// An output file that appears only when complete: the content goes to a temporary file in
// the target's directory, which commit() renames onto the target (std::filesystem::rename,
// atomic on POSIX). Until then, and on any failure, the target is untouched; the
// destructor removes an uncommitted temporary.

#include <filesystem>
#include <string>

namespace snaresim::render
{

class AtomicFile
{
public:
    // Creates the (empty) temporary file at once, so that an unusable target (missing
    // directory, no permission, target is a directory) fails before any work.
    // Throws UserError.
    explicit AtomicFile(std::filesystem::path target);
    ~AtomicFile();

    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    const std::filesystem::path& target() const { return targetPath; }
    const std::filesystem::path& temporary() const { return tempPath; }

    // For messages: the target as the user gave it, in quotes.
    std::string displayName() const;

    // Renames the temporary onto the target. Throws UserError.
    void commit();

    // Removes the committed target again (when a later output of the same run failed).
    void discardCommitted() noexcept;

    bool committed() const { return isCommitted; }

private:
    std::filesystem::path targetPath;
    std::filesystem::path tempPath;
    bool isCommitted = false;
};

} // namespace snaresim::render
