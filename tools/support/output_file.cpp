// sphbasis CLI support: write_file_atomic (see output_file.hpp).
#include "output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace sphbasis::cli {

namespace {

std::atomic<unsigned long> g_counter{0};

std::runtime_error write_error(const std::string& path, int err) {
    return std::runtime_error("cannot write '" + path + "': " + std::strerror(err));
}

}  // namespace

std::string temporary_name_for(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
    const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
    return dir + "." + base + ".tmp-" + std::to_string(static_cast<long>(::getpid())) + "-" +
           std::to_string(g_counter.fetch_add(1));
}

void discard_temporary(const std::string& temp) noexcept { std::remove(temp.c_str()); }

void commit_temporary(const std::string& temp, const std::string& path) {
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        discard_temporary(temp);
        throw write_error(path, err);
    }
}

std::string write_temporary(const std::string& path, const void* data, std::size_t size,
                            bool sync) {
    const std::string temp = temporary_name_for(path);
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) throw write_error(path, errno);
    const char* p = static_cast<const char*>(data);
    std::size_t left = size;
    int err = 0;
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            err = errno;
            break;
        }
        p += n;
        left -= static_cast<std::size_t>(n);
    }
    if (err == 0 && sync && ::fsync(fd) != 0) err = errno;
    // close() reports delayed write errors (NFS, ENOSPC on some file systems).
    if (::close(fd) != 0 && err == 0) err = errno;
    if (err != 0) {
        discard_temporary(temp);
        throw write_error(path, err);
    }
    return temp;
}

void write_file_atomic(const std::string& path, const void* data, std::size_t size, bool sync) {
    commit_temporary(write_temporary(path, data, size, sync), path);
}

void check_writable(const std::string& path) {
    discard_temporary(write_temporary(path, "", 0, false));
}

void OutputFiles::commit(bool sync) {
    std::vector<std::string> temps;
    try {
        for (const auto& f : files_)
            temps.push_back(write_temporary(f.first, f.second.data(), f.second.size(), sync));
    } catch (...) {
        for (const auto& t : temps) discard_temporary(t);
        throw;
    }
    for (std::size_t i = 0; i < temps.size(); ++i) {
        try {
            commit_temporary(temps[i], files_[i].first);
        } catch (...) {
            for (std::size_t j = i + 1; j < temps.size(); ++j) discard_temporary(temps[j]);
            throw;
        }
    }
    files_.clear();
}

std::string join_path(const std::string& dir, const std::string& name) {
    return dir.empty() || dir == "." ? name : (dir.back() == '/' ? dir + name : dir + "/" + name);
}

void ensure_dir(const std::string& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir))
        throw std::runtime_error("cannot create output directory '" + dir + "'" +
                                 (ec ? ": " + ec.message() : std::string()));
}

}  // namespace sphbasis::cli
