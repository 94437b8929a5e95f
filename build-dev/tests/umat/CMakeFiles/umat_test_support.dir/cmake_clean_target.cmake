file(REMOVE_RECURSE
  "libumat_test_support.a"
)
