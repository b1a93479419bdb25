; inputs finite with |x| <= 65536 (other batches run the general code)
; 4 points per iteration (xmm registers)
L0:
     0    push rbx
     1    push rbp
     2    push r12
     4    push r13
     6    push r14
     8    push r15
     a    sub rsp, 504
    11    mov rbx, rdi
    14    mov r12, rsi
    17    mov r15, r8
    1a    lea r13, [rdx+rdx*2]
    1e    add r13, rdx
    21    lea r14, [rcx+rcx*2]
    25    add r14, rcx
L2:
    28    cmp r13, r14
    2b    jae L3
L4:
    31    mov rax, [rbx]
    34    movups xmm2, [rax+r13*1]
    39    mov rax, [rbx+8]
    3d    movups xmm3, [rax+r13*1]
    42    mov rax, [rbx+16]
    46    movups xmm4, [rax+r13*1]
    4b    minps xmm3, xmm2
    4e    mulps xmm4, xmm4
    51    addps xmm4, [rip+L6]
    58    sqrtps xmm2, xmm4
    5b    subps xmm3, xmm2
    5e    mov rax, [r12]
    62    movups [rax+r13*1], xmm3
L5:
    67    add r13, 16
    6b    jmp L2
L3:
    70    mov rax, 0x0
L1:
    75    add rsp, 504
    7c    pop r15
    7e    pop r14
    80    pop r13
    82    pop r12
    84    pop rbp
    85    pop rbx
    86    ret
L6:
    90    .float 1, 1, 1, 1
