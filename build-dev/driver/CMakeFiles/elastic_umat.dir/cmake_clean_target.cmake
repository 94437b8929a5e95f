file(REMOVE_RECURSE
  "libelastic_umat.a"
)
