#pragma once
// The one error type of Overflight. Every failure a user can cause (bad file,
// bad camera, bad option) is reported as `Error`, whose what() is a single
// line "SUBJECT: problem" where SUBJECT names the file or option at fault.
// The `overflight` app prints it as "overflight: SUBJECT: problem" and exits 1.
#include <stdexcept>
#include <string>

namespace overflight {

class Error : public std::runtime_error {
public:
    Error(const std::string& subject, const std::string& problem)
        : std::runtime_error(subject + ": " + problem), subject_(subject), problem_(problem) {}
    const std::string& subject() const { return subject_; }
    const std::string& problem() const { return problem_; }

private:
    std::string subject_;
    std::string problem_;
};

} // namespace overflight
