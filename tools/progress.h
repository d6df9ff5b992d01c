#pragma once
// A one-line progress bar on stderr for long work (batches, playback, sweeps), drawn only
// when stderr is a terminal, so logs and pipes get only the messages.
#include <string>

namespace manylight {

class Progress {
 public:
  explicit Progress(int total);  // total 0: not known, counted only
  ~Progress() { clear(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Starts item number done()+1, named `what`.
  void step(const std::string& what);
  // Erases the bar (before printing a message, and at the end).
  void clear();
  int done() const { return done_; }

 private:
  int total_;
  int done_ = 0;
  bool terminal_;
  bool drawn_ = false;
};

}  // namespace manylight
