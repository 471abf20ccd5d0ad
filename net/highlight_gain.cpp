#include "net/highlight_gain.h"

#include "core/errors.h"

#include <string>

namespace lh::net {

void validateHighlightGain(double gain) {
    if (!(gain >= 1.0 && gain <= kMaxHighlightGain))  // NaN too
        throw InputError("--highlight-gain must be in [1, " +
                         std::to_string(int(kMaxHighlightGain)) + "]");
}

void validateHighlightKnee(double knee) {
    if (!(knee >= 1.0 && knee <= kMaxHighlightKnee))  // NaN too
        throw InputError("--highlight-knee must be in [1, " +
                         std::to_string(int(kMaxHighlightKnee)) + "] (luminance; 1 is white)");
}

}  // namespace lh::net
