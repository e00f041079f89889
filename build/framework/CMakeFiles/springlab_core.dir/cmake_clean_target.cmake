file(REMOVE_RECURSE
  "libspringlab_core.a"
)
