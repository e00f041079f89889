file(REMOVE_RECURSE
  "libspringlab_rope_reference.a"
)
