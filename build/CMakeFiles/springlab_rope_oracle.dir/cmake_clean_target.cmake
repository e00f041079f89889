file(REMOVE_RECURSE
  "libspringlab_rope_oracle.a"
)
