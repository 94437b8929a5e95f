file(REMOVE_RECURSE
  "libdriver_core.a"
)
