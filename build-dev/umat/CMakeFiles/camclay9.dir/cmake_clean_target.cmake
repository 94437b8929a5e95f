file(REMOVE_RECURSE
  "libcamclay9.a"
)
