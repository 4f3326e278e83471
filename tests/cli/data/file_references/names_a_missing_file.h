// The check's own test: this comment names a header that is not in the repository,
// engine/lighting/common/no_such_layout.h, beside one that is (engine/session/session.h).
