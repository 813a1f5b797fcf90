#include "cancel_token.h"

namespace gbl {

void CancelToken::cancel(int signal) {
    std::lock_guard lock(actionMutex_);
    if (signal <= 0) signal = 1;  // 0 means "not asked"
    int none = 0;
    if (!signal_.compare_exchange_strong(none, signal)) return;
    if (action_) action_(signal);
}

void CancelToken::setAction(std::function<void(int signal)> action) {
    std::lock_guard lock(actionMutex_);
    action_ = std::move(action);
}

}  // namespace gbl
