file(REMOVE_RECURSE
  "libspringlab_rope_student.a"
)
