#pragma once
// Thrown by the stub of an exercise a student has not written yet. The viewer shows its
// message on screen and keeps running; tests report it as a missing exercise.
#include <stdexcept>
#include <string>

namespace springlab {

class NotImplemented : public std::logic_error {
 public:
  NotImplemented(std::string exerciseId, std::string title, std::string handoutSection)
      : std::logic_error("not implemented: exercise " + exerciseId + " (" + title + "), see " +
                         handoutSection),
        exerciseId_(std::move(exerciseId)),
        title_(std::move(title)),
        handoutSection_(std::move(handoutSection)) {}

  const std::string& exerciseId() const { return exerciseId_; }
  const std::string& title() const { return title_; }
  const std::string& handoutSection() const { return handoutSection_; }

 private:
  std::string exerciseId_;
  std::string title_;
  std::string handoutSection_;
};

}  // namespace springlab
