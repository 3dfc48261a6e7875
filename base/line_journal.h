// An append-only journal of finished work that survives a hard kill (SIGKILL, power loss): one
// record per line, each made durable (fsync) before Append returns, so that a long run killed at
// any instant can be resumed from the records it finished.
//
// File format (text): the first line "# topoplan journal 1: <configuration>", then one line per
// record "<payload>\t<checksum>", where checksum is the 16 lower-case hex digits of the 64-bit
// FNV-1a hash of the payload bytes. On opening, a last line without its newline or whose checksum
// does not match (a write torn by the kill) is dropped and cut off the file; a damaged line
// followed by intact ones is refused (the file was changed by something else).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace base {

// 64-bit FNV-1a hash of `bytes` (offset basis 14695981039346656037, prime 1099511628211).
std::uint64_t Fnv1a64(const std::string& bytes);

class LineJournal {
 public:
  // Opens the journal at `path`, creating it (with its folder's entry made durable) when absent,
  // and reads the records it holds. `configuration` (one line, no '\n') names what the records
  // were made with; a journal written with another configuration is refused. Throws
  // std::invalid_argument "<path>: ..." for another configuration ("... was written by another
  // configuration ('<theirs>'; this run: '<ours>'); remove it or use another output folder"),
  // a damaged record before the last line ("<path>:<line>: damaged record ...") or a file that is
  // not a journal; base::WriteError when the system refuses to write it.
  LineJournal(const std::string& path, const std::string& configuration);
  ~LineJournal();
  LineJournal(const LineJournal&) = delete;
  LineJournal& operator=(const LineJournal&) = delete;

  const std::string& path() const { return path_; }
  // Payloads of the intact records found when opening, in file order.
  const std::vector<std::string>& records() const { return records_; }
  // Whether a torn last line was dropped (and cut off) when opening.
  bool dropped_torn_line() const { return dropped_torn_line_; }

  // Appends one record and makes it durable (write, then fsync) before returning. `payload` must
  // not hold '\n' or '\t' (std::invalid_argument). Throws base::WriteError when the write fails.
  void Append(const std::string& payload);

  // Closes and deletes the journal (after its records reached the run's final outputs).
  void Remove();

 private:
  std::string path_;
  int fd_ = -1;
  std::vector<std::string> records_;
  bool dropped_torn_line_ = false;
};

}  // namespace base
